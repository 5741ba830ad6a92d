//! `auto`'s tuning constants: what each sets and what it trades off (the module doc of
//! [`crate::auto`] says how the pilot uses them; docs/auto.md, "Parameters", lists them, and
//! docs/measurements/auto.md measures how well `auto` chooses with them).

/// Share of a time budget the unguided pilot takes (and the guides' pilot passes together):
/// more pilot passes predict better but leave less time to the chosen method
/// (docs/auto.md, "The pilot").
pub const PILOT_SHARE: f64 = 0.04;
/// Guided candidates are piloted only when the scene is hard enough
/// ([`GUIDED_MIN_PASS_VARIANCE`]) and their maps are predicted to take at most this share of
/// the budget, all guides piloted so far included...
pub const GUIDED_MAPS_SHARE: f64 = 0.15;
/// ...or, for the first guide piloted (the paper's footprints), this share. Where a scene is
/// hard, guiding wins by several times, and a first guide left unpiloted leaves `auto` with
/// an unguided method far behind it (door's footprint maps and pilot do not fit
/// [`GUIDED_MAPS_SHARE`]); a larger share takes more of the budget from the method that
/// renders. Measured: docs/measurements/auto.md, "door at 256x256".
pub const FIRST_GUIDE_MAPS_SHARE: f64 = 0.3;
/// The share of the maps' particle paths the pilot shoots to time their passes before it
/// decides whether the first guide's maps fit (`particle_pass_seconds`, which shoots at
/// least four chunks of paths per worker): a sixteenth of passes that may then run in full.
pub const PROBE_SHARE: f64 = 1.0 / 16.0;
/// The map and cache builds' time over the particle passes' that the first guide's maps are
/// estimated with: 0.2 to 1.7 measured (Veach MIS 0.2, Veach Bidir 1.5, the slit room 1.4
/// for `pt-footprint`'s maps and 1.7 for `combined-footprint`'s, 16 s budgets); the high
/// end, so that a guide is piloted only where its maps fit.
pub const MAPS_BUILD_FACTOR: f64 = 1.7;
/// Guided candidates are piloted only where one pass of the unguided candidate the pilot
/// predicts best has at least this relative variance (the metric's, averaged over pixels
/// and channels: about the squared relative noise of one sample per pixel). Below it the
/// image converges without guiding, and a guided pilot (maps, caches and passes) costs more
/// than guiding wins. Measured at 16 s: the furnace 0.00, the Cornell boxes 0.4, desk 0.8,
/// the public rooms 0.7-1.4, glass 1.5, Veach Bidir 1.8-2.8 and the living room 2.3-2.5
/// (guided path tracing even or behind); Veach MIS 0.8-9.8 from one pilot to the next
/// (guided path tracing at about half `pt-bsdf`'s error); the slit room, Veach Ajar and
/// door far above. At 10 the
/// gate left Veach MIS unpiloted on most runs (`auto` 2.2x the best method's error); at 4
/// its guides are piloted on some (1.22x), and the breakfast room (about 9.7) pays for a
/// guided pilot (1.2x): docs/auto.md, "The pilot", and docs/measurements/auto.md.
pub const GUIDED_MIN_PASS_VARIANCE: f64 = 4.0;
/// Where no guide's maps fit their share of a short budget, a scene on which path tracing is
/// at least this hard per sample (one pass of `pt-bsdf` at this relative variance) renders
/// guided path tracing with the first guide unpiloted rather than the best unguided
/// candidate, unless light tracing is that candidate or path tracing misses light: on Veach
/// Ajar at 8 s the guided pilot often does not fit 30% of the budget, and the unguided method
/// `auto` rendered had 3-5x guided path tracing's error (docs/auto.md, "The choice"). The
/// scenes this hard read 22-29 (Veach Ajar at 128x72, from one pilot to the next), 45 (the
/// slit room) and about 190 (door at 128x128), and guided path tracing wins on them at 2-4x;
/// those where guiding is even or behind read under 10 (the list at
/// [`GUIDED_MIN_PASS_VARIANCE`]; Veach MIS up to 9.8, whose maps fit a pilot at 8 s). A wrong
/// bet costs what guiding costs where it does not pay, 1.0-1.4x; a right one wins 2-4x.
pub const HARD_PASS_VARIANCE: f64 = 10.0;
/// A guided candidate is chosen only when predicted better than BSDF sampling of its own
/// integrator by this factor (else the next candidate is). The pilot's passes are
/// independent samples, but the render's are a Sobol sequence, whose stratification gains
/// BSDF sampling more over thousands of passes than guided sampling, and which a short
/// pilot cannot measure; where guiding helps it wins by far more than the margin. Against
/// the other direction the margin does not apply: on door `lt-footprint` wins over `pt-bsdf`
/// by far more than its prediction says, and a margin against the best unguided method of
/// either direction would choose `pt-bsdf` there. docs/auto.md, "The choice".
pub const GUIDED_MARGIN: f64 = 1.3;
/// A guided combined image is chosen only when predicted better than the better of its own
/// guide's path and light tracer by this factor (else the next candidate is). The combined
/// image's prediction runs low against theirs, also with the splitting directions piloted
/// as they render ([`SplitPilot`](super::split::SplitPilot)): on Veach Ajar it is predicted
/// about as good as `pt-footprint`, which renders it with less error
/// (docs/measurements/veach-ajar.md; docs/auto.md, "The choice").
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
/// [`pilot_passes`](super::pilot::pilot_passes)), so that no pilot time goes to passes
/// thrown away. Their layers count as every pass's; at least [`MIN_BATCHES`] (unguided) or
/// two (guided) passes with the second-moment layers follow, and what a candidate's own
/// paths missed is measured on those (both second-moment layers from the same passes). Two,
/// as other jobs on the machine only slow a pass down: more would time better but leave
/// fewer passes with the second-moment layers. docs/auto.md, "The pilot".
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
/// with the image while the budget does not. One pass of a method has about the same
/// relative variance per pixel at either resolution (one path per pixel, the same paths; a
/// light pass traces one path per pixel, and each of its splats carries the pixel count's
/// share), while its time scales with the pixel count: the pilot's pass times are scaled by
/// the ratio of the pixel counts, which leaves the ranking as measured and predicts each
/// candidate's error at the image's resolution. The maps are not tied to the resolution
/// (the view pass draws raster positions uniformly over the image; its importance target
/// is the image's where the time allows, [`FULL_TARGET_SHARE`]), so a guided winner still
/// reuses them. A smaller limit costs more per path (a pass's fixed costs weigh more), which
/// makes the footprints' maps look too dear to pilot on door. docs/auto.md, "The pilot";
/// measured: docs/measurements/auto.md, "door at 256x256".
pub const PILOT_MAX_PIXELS: usize = 128 * 128;
/// A pilot at a lower resolution ([`PILOT_MAX_PIXELS`]) builds the view pass's importance
/// target ([`crate::passes::target`]) at the image's resolution when the extra passes that
/// takes are predicted at most this share of the rendering time left, and the first guide's
/// maps still fit [`FIRST_GUIDE_MAPS_SHARE`] with them (never at the footprints' cost;
/// unless every candidate is guided, when the maps are piloted whatever they cost). The
/// target at the pilot's resolution is coarser than the image whose relative error it
/// weighs, and maps built with it guide the light tracer worse per pass; the target at the
/// image's resolution costs passes of its own. docs/auto.md, "The pilot"; measured:
/// docs/measurements/auto.md, "door at 256x256".
pub const FULL_TARGET_SHARE: f64 = 0.08;
