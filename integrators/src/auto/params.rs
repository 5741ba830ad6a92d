//! `auto`'s tuning constants, each with what was measured to set it (the module doc of
//! [`crate::auto`] says how the pilot uses them).

/// Share of a time budget the unguided pilot takes.
pub const PILOT_SHARE: f64 = 0.04;
/// Guided candidates are piloted only when the scene is hard enough
/// ([`GUIDED_MIN_PASS_VARIANCE`]) and their maps are predicted to take at most this share of
/// the budget, all guides piloted so far included...
pub const GUIDED_MAPS_SHARE: f64 = 0.15;
/// ...or, for the first guide piloted (the paper's footprints), this share: where a scene is
/// hard, guiding won by 3-10x, and door's footprint maps and pilot (3.4 s of 16 s on a slow
/// day of the 2-core VM) no longer fitted 15%, which left `auto` with unguided light tracing
/// there (4-4.6x behind `lt-footprint`). 0.25 until Russian roulette started at depth 8
/// (thirteenth session): door's light paths grew longer (maps 1.6 → 2.6 s), its estimate
/// came to 4.06 s of 16, and `auto` chose `pt-bsdf` at 4x `lt-footprint`'s error.
pub const FIRST_GUIDE_MAPS_SHARE: f64 = 0.3;
/// Guided candidates are piloted only where one pass of the unguided candidate the pilot
/// predicts best has at least this relative variance (the metric's, averaged over pixels
/// and channels: about the squared relative noise of one sample per pixel). Below it the
/// image converges without guiding, and a guided pilot (maps, caches and passes: 24-29% of
/// a 16-s budget on cornell) costs more than guiding wins. Measured (one pass of the best
/// unguided method): furnace 0.02, Bitterli's Cornell box 0.4, cornell 0.8, features 1.5,
/// desk 2.8 (guided methods lose or tie at equal time on all five) against Veach Ajar 48
/// and door 2650 (guided methods 3-10x ahead); README "auto: the renderer chooses".
pub const GUIDED_MIN_PASS_VARIANCE: f64 = 10.0;
/// A guided candidate is chosen only when predicted better than BSDF sampling of its own
/// integrator by this factor (else the next candidate is). The pilot's passes are
/// independent samples, but the render's are a Sobol sequence, whose stratification gains
/// BSDF sampling more over thousands of passes than guided sampling (cornell, 16 s: Sobol
/// against independent numbers 2.0x less error for `pt-bsdf`, 1.5x for `pt-footprint`),
/// and which a short pilot cannot measure (4-6 passes per randomisation showed 1.2x for
/// both); where guiding helps it wins by far more (Veach Ajar, door: 3-10x). Against the
/// other direction the margin does not apply: on door `lt-footprint` wins over `pt-bsdf`
/// by far more than its prediction says, and a margin against the best unguided method of
/// either direction chose `pt-bsdf` there (6x behind).
pub const GUIDED_MARGIN: f64 = 1.3;
/// A guided combined image is chosen only when predicted better than the better of its own
/// guide's path and light tracer by this factor (else the next candidate is). Set when the
/// pilot measured all three unsplit, from the combined image's layers (door 16 s, seed 2:
/// `combined-footprint` predicted 0.730 and `lt-footprint` 0.736, rendered 0.67-1.31
/// against 0.30-0.35); kept now that the splitting directions are piloted as they render
/// ([`SplitPilot`](super::split::SplitPilot)): on Veach Ajar (30 s) the combined image is
/// still predicted about as good as `pt-footprint` (seeds 1-3 of the thirteenth session:
/// 0.97x, 1.04x and 1.29x its prediction) where 30-s renders of the two measure 1.05-1.4x
/// apart in `pt-footprint`'s favour on most seeds; a `compare` run of seed 2 chose the
/// combined image even so, at 1.24x `pt-footprint`'s error.
pub const SPLIT_MARGIN: f64 = 1.3;
/// A guided path or light tracer that splits is piloted with passes of its own
/// ([`SplitPilot`](super::split::SplitPilot)) for this share of its guide's combined
/// pilot's time each, and at least [`MIN_SPLIT_PASSES`] of them.
pub const SPLIT_PILOT_SHARE: f64 = 0.5;
pub const MIN_SPLIT_PASSES: usize = 3;
/// Fewest and most pilot passes per set of candidates (the unguided pilot's fewest with
/// the second-moment layers; [`TIMED_PASSES`] more run before them).
pub const MIN_BATCHES: usize = 4;
/// The first passes of each combined pilot render without the second-moment layers, as the
/// combined image renders, and time it (the fastest of them,
/// [`pilot_passes`](super::pilot::pilot_passes)): two passes that timed it apart were
/// thrown away (door, 16 s: 0.5 s of a 6.5-s pilot). Their layers count as every pass's; at
/// least [`MIN_BATCHES`] (unguided) or two (guided) passes with the second-moment layers
/// follow, and what a candidate's own paths missed is measured on those (both second-moment
/// layers from the same passes). Two, as other jobs on the machine only slow a pass down.
/// Veach Ajar at 30 s, seeds 2 and 3, predicted `pt-footprint` 1.08e-2 and 7.7e-3 so,
/// 1.12e-2 and 7.1e-3 with one timed pass, 1.21e-2 and 8.9e-3 with the timing passes apart
/// (every pass in the second-moment layers): within what one seed's pilot varies from run
/// to run (1.1-1.8e-2 on seed 2).
pub const TIMED_PASSES: usize = 2;
pub const MAX_BATCHES: usize = 48;
/// A time budget shorter than this many passes of pt and lt together leaves no room for a
/// pilot (its least cost is about 7 such pairs): the first unguided candidate renders.
pub const MIN_BUDGET_PAIRS: f64 = 40.0;
/// The pilot's passes are dealt to this many folds (pass `b` to fold `b % FOLDS`): the
/// squared deviations of a fold's passes are weighed with `R` from every other pass
/// ([`measure`](super::predict::measure)).
pub const FOLDS: usize = 4;
/// Pilot samples per block of pixels on which missing light is measured (see
/// [`measure`](super::predict::measure)).
pub const BIAS_BLOCK_SAMPLES: f64 = 64.0;
/// An image of more pixels than this is piloted at a lower resolution
/// ([`pilot_resolution`](super::pilot_resolution)), the same view through fewer, larger
/// pixels. The pilot's least passes (six unguided, four guided combined and three split per
/// direction) and the view pass's importance target render every pixel, so their cost grows
/// with the image while the budget does not: door at its own 256x256 and 16 s piloted for
/// 11-13 s (its pixels four times those of the 128x128 at which `auto` was tuned), and
/// `auto`'s error was 2.7-5.4x `lt-footprint`'s (README "`auto` against the fixed
/// methods"). One pass of a method has about the same relative variance per pixel at either
/// resolution (one path per pixel, the same paths; a light pass traces one path per pixel,
/// and each of its splats carries the pixel count's share), while its time scales with the
/// pixel count: the pilot's pass times are scaled by the ratio of the pixel counts, which
/// leaves the ranking as measured and predicts each candidate's error at the image's
/// resolution. The maps are not tied to the resolution (the view pass draws raster
/// positions uniformly over the image; its importance target is the image's where the time
/// allows, [`FULL_TARGET_SHARE`]), so a guided winner still reuses them. 64x64 was tried:
/// door's passes of 4096 pixels took longer per path (a pass's fixed costs), the
/// footprints' maps were estimated at 5.1 s, over their 30% of 16 s, and `auto` chose
/// `pt-bsdf` at 3.5x `lt-footprint`'s error.
pub const PILOT_MAX_PIXELS: usize = 128 * 128;
/// A pilot at a lower resolution ([`PILOT_MAX_PIXELS`]) builds the view pass's importance
/// target ([`crate::passes::target`]) at the image's resolution when the extra passes that takes
/// are predicted at most this share of the rendering time left, and the first guide's maps
/// still fit [`FIRST_GUIDE_MAPS_SHARE`] with them (never at the footprints' cost; unless
/// every candidate is guided, when the maps are piloted whatever they cost). The target at
/// the pilot's resolution is coarser than the image whose relative error it weighs, and
/// maps built with it guide the light tracer worse per pass: door 256x256, 120 light
/// passes, seeds 11-13, `lt-footprint` with the pilot's maps 0.379, 0.375, 0.439 against
/// its own maps' 0.364, 0.383, 0.348 (1.09x on average, so about 8% of the passes are
/// lost); with the target at the image's resolution, door at 32 s had 0.98-1.03x the fixed
/// method's error per pass. Its four passes at 256x256 cost door 0.6-1.0 s more than at
/// 128x128. Door 256x256 against `lt-footprint` (nineteenth session, README "Nineteenth
/// session"): at 16 s (0.63 s estimated against 0.83 s) seeds 1-12 read 0.76-1.39x, median
/// 1.29 (seeds 1-6: 1.21-1.35x where the coarse target read 1.24-1.50x and misranked seed
/// 1, 4.8x; a later run of seed 1 with the target misranked it too); at 32 s, seeds 1-4,
/// 1.07-1.22x against 1.23-1.30x; at 64 s, seeds 1-2, 1.17 and 1.03x.
pub const FULL_TARGET_SHARE: f64 = 0.08;
