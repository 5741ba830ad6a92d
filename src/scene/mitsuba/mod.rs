//! Mitsuba 3 scene import: `footprint render scene.xml` reads the scenes researchers already
//! keep (Bitterli's collection, the path-guiding papers' suites) and renders what Mitsuba 3
//! renders from them.
//!
//! Read: `<default>` parameters with `$name` substitution (overridden by `-D name=value`),
//! `id`/`<ref>`, `to_world` transforms, the `perspective` sensor (`fov`, `fov_axis`) with its
//! `hdrfilm` (size, `box`/`tent`/`gaussian` filter) and sampler (`sample_count`), the `path`
//! (and `ptracer`) integrator's `max_depth`; shapes `obj`, `ply`, `serialized`, `rectangle`,
//! `cube`, `disk`, `sphere`, `cylinder`; BSDFs `diffuse`, `twosided`, `bumpmap`, `dielectric`,
//! `thindielectric`, `roughdielectric`, `conductor`, `roughconductor`, `plastic`,
//! `roughplastic`, `principled`; textures `bitmap` (also `raw`) and `checkerboard` (with `to_uv`); emitters
//! `area`, `point`, `spot`, `constant`, `directional`, `envmap`. Anything else stops the
//! import with an error naming the element, its line and what is supported, unless
//! `--lenient`, which replaces it with the stand-in the error names and lists every
//! replacement. `docs/mitsuba.md` tables the mapping.
//!
//! The import reads the document in `import.rs`, into a builder (`builder.rs`) that each
//! element's file extends: `integrator.rs`, `sensor.rs` (with the film, sampler and pixel
//! filter), `texture.rs`, `bsdf.rs` (with `bumpmap.rs` and `principled.rs`), `shape.rs` (the meshes of
//! `meshes.rs`, `ply.rs` and `serialized.rs`) and `emitter.rs`. `xml.rs` holds the typed
//! property lookup, `prefetch.rs` loads the files ahead, and `export.rs` writes a scene back
//! out as Mitsuba 3 XML.

mod bsdf;
mod builder;
mod bumpmap;
mod conductors;
mod emitter;
pub mod export;
mod import;
mod integrator;
mod meshes;
mod ply;
mod prefetch;
mod principled;
mod sensor;
mod serialized;
mod shape;
mod texture;
mod xml;

pub use import::{ImportOptions, load, parse_define};
pub use meshes::MeshData;
