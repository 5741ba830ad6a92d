//! The readers' fuzz harnesses: one function a reader, each taking arbitrary bytes, writing
//! them as the reader's file(s) in a scratch folder and reading them back the way the
//! command line does. The cargo-fuzz targets of `fuzz/` call these, and so does
//! `tests/fuzz_corpus.rs`, which replays the committed corpus and every crash input found
//! on stable Rust (docs/testing.md, "Fuzzing").
//!
//! A harness returns the reader's error as text (`Err`), so a test can check that the
//! error names the file; any panic, hang or unbounded allocation is a finding.
//!
//! An input may hold several files, separated by [`SEPARATOR`] lines: a scene and the
//! meshes it names. Each target says what its files are called ([`TOML_FILES`],
//! [`XML_FILES`], [`OBJ_FILES`], [`PLY_FILE`], [`SERIALIZED_FILE`], [`SHARD_FILES`]).

use std::path::{Path, PathBuf};

/// The line between the files of one input.
pub const SEPARATOR: &[u8] = b"\n#%%next-file%%\n";

/// A TOML scene, then the OBJ and MTL it may name.
pub const TOML_FILES: &[&str] = &["scene.toml", "mesh.obj", "mesh.mtl"];
/// A Mitsuba 3 XML scene, then the OBJ and texture it may name.
pub const XML_FILES: &[&str] = &["scene.xml", "mesh.obj", "texture.png"];
/// An OBJ file, its MTL and a texture the MTL may name, read through a fixed TOML scene.
pub const OBJ_FILES: &[&str] = &["mesh.obj", "mesh.mtl", "texture.png"];
/// A PLY mesh, read through a fixed Mitsuba scene.
pub const PLY_FILE: &str = "mesh.ply";
/// A `.serialized` mesh file, read through a fixed Mitsuba scene.
pub const SERIALIZED_FILE: &str = "mesh.serialized";
/// Shard images of one merge (at most this many).
pub const SHARD_FILES: &[&str] = &["shard0.exr", "shard1.exr", "shard2.exr", "shard3.exr"];

/// The TOML scene that reads the OBJ target's mesh.
const OBJ_SCENE: &str = "[camera]\nposition = [0.5, 0.5, -2.0]\nlook_at = [0.5, 0.5, 0.0]\nfov_y = 40.0\nresolution = [8, 8]\n[[light]]\ntype = \"point\"\nposition = [0.5, 2.0, -1.0]\nintensity = [1.0, 1.0, 1.0]\n[[mesh]]\nfile = \"mesh.obj\"\n";

/// Splits an input at [`SEPARATOR`] into at most `n` files (the last keeps any further
/// separators).
pub fn split(data: &[u8], n: usize) -> Vec<&[u8]> {
    let mut parts = Vec::new();
    let mut rest = data;
    while parts.len() + 1 < n {
        match rest.windows(SEPARATOR.len()).position(|w| w == SEPARATOR) {
            Some(i) => {
                parts.push(&rest[..i]);
                rest = &rest[i + SEPARATOR.len()..];
            }
            None => break,
        }
    }
    parts.push(rest);
    parts
}

/// Joins files into one input (the inverse of [`split`]; the seed corpus is made with it).
pub fn join(files: &[&[u8]]) -> Vec<u8> {
    let mut out = Vec::new();
    for (i, f) in files.iter().enumerate() {
        if i > 0 {
            out.extend_from_slice(SEPARATOR);
        }
        out.extend_from_slice(f);
    }
    out
}

/// A scratch folder of this process and thread, emptied.
fn scratch(target: &str) -> PathBuf {
    let thread = format!("{:?}", std::thread::current().id());
    let thread: String = thread.chars().filter(|c| c.is_ascii_digit()).collect();
    let d = std::env::temp_dir().join(format!(
        "footprint-fuzz-{}-{thread}-{target}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("a scratch folder in the temporary directory");
    d
}

/// Writes the parts of `data` as `names` in a fresh scratch folder.
fn write_files(target: &str, data: &[u8], names: &[&str]) -> PathBuf {
    let d = scratch(target);
    for (name, part) in names.iter().zip(split(data, names.len())) {
        std::fs::write(d.join(name), part).expect("a scratch file");
    }
    d
}

fn scene(path: &Path) -> Result<(), String> {
    footprint::scene::load::load_scene(path)
        .map(drop)
        .map_err(|e| e.to_string())
}

/// The TOML scene reader ([`footprint::scene::toml_file`]) with its OBJ/MTL.
pub fn toml_scene(data: &[u8]) -> Result<(), String> {
    let d = write_files("toml", data, TOML_FILES);
    scene(&d.join(TOML_FILES[0]))
}

/// The Mitsuba 3 XML importer ([`footprint::scene::mitsuba`]) with an OBJ and a texture.
pub fn mitsuba_scene(data: &[u8]) -> Result<(), String> {
    let d = write_files("xml", data, XML_FILES);
    scene(&d.join(XML_FILES[0]))
}

/// The OBJ/MTL reader (tobj and the checks around it), through a fixed TOML scene.
pub fn obj(data: &[u8]) -> Result<(), String> {
    let d = write_files("obj", data, OBJ_FILES);
    std::fs::write(d.join("scene.toml"), OBJ_SCENE).expect("a scratch file");
    scene(&d.join("scene.toml"))
}

/// A Mitsuba scene of an 8x8 film, an area light and `shape`, the mesh a target reads.
fn mesh_scene(shape: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
  <sensor type="perspective">
    <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><translate z="3"/></transform>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
  {shape}
</scene>
"#
    )
}

/// The PLY reader (`footprint::scene::mitsuba`'s `ply.rs`): the input is the file, read by
/// a fixed Mitsuba scene's `<shape type="ply">`.
pub fn ply(data: &[u8]) -> Result<(), String> {
    let d = scratch("ply");
    std::fs::write(d.join(PLY_FILE), data).expect("a scratch file");
    let shape =
        format!(r#"<shape type="ply"><string name="filename" value="{PLY_FILE}"/></shape>"#);
    std::fs::write(d.join("scene.xml"), mesh_scene(&shape)).expect("a scratch file");
    scene(&d.join("scene.xml"))
}

/// The `.serialized` reader (`footprint::scene::mitsuba`'s `serialized.rs`): the first
/// byte picks the mesh (`shape_index` = byte % 4, so that the fuzzer reaches the table of
/// offsets), the rest is the file, read by a fixed Mitsuba scene's
/// `<shape type="serialized">`.
pub fn serialized(data: &[u8]) -> Result<(), String> {
    let d = scratch("serialized");
    let (index, file) = data.split_first().unwrap_or((&0, &[]));
    std::fs::write(d.join(SERIALIZED_FILE), file).expect("a scratch file");
    let shape = format!(
        r#"<shape type="serialized"><string name="filename" value="{SERIALIZED_FILE}"/><integer name="shape_index" value="{}"/></shape>"#,
        index % 4
    );
    std::fs::write(d.join("scene.xml"), mesh_scene(&shape)).expect("a scratch file");
    scene(&d.join("scene.xml"))
}

/// The maps file reader ([`crate::maps_file::load`]). The first byte chooses what the rest
/// is: bit 0 clear, the whole file as it is; set, the payload, given the header a saved
/// file has (magic, version, length and checksum), so that the fuzzer reaches the passes
/// behind the checksum. Bit 1 clear, the file is loaded with the key it holds; set, with
/// [`MAPS_KEY`] (the mismatch's message).
pub fn maps_file(data: &[u8]) -> Result<(), String> {
    let d = scratch("maps");
    let path = d.join("maps.fpm");
    let (mode, rest) = data.split_first().unwrap_or((&0, &[]));
    let (file, mut key) = if mode & 1 == 0 {
        (
            rest.to_vec(),
            payload_key(rest.get(52..).unwrap_or_default()),
        )
    } else {
        (with_header(rest), payload_key(rest))
    };
    if mode & 2 != 0 {
        key = MAPS_KEY.to_string();
    }
    std::fs::write(&path, file).expect("a scratch file");
    crate::maps_file::load(&path, &key)
        .map(drop)
        .map_err(|e| format!("{e:#}"))
}

/// The key a maps file is loaded with when the input's first byte has bit 1 set.
pub const MAPS_KEY: &str =
    "scene=0123456789abcdef0123456789abcdef resolution=4x4 max_depth=8 seed=0 photons=40";

/// A maps file of `payload` with a good header.
pub fn with_header(payload: &[u8]) -> Vec<u8> {
    let mut file = Vec::new();
    file.extend_from_slice(crate::maps_file::MAGIC);
    file.extend_from_slice(&crate::maps_file::VERSION.to_le_bytes());
    file.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    file.extend_from_slice(blake3::hash(payload).as_bytes());
    file.extend_from_slice(payload);
    file
}

/// The key at the start of a payload (u32 length and UTF-8), or "" if there is none.
fn payload_key(payload: &[u8]) -> String {
    let Some(n) = payload.get(..4) else {
        return String::new();
    };
    let n = u32::from_le_bytes(n.try_into().unwrap()) as usize;
    payload
        .get(4..4usize.saturating_add(n))
        .and_then(|k| std::str::from_utf8(k).ok())
        .unwrap_or_default()
        .to_string()
}

/// The shard merge ([`crate::merge::merge`]) of up to four shard EXRs.
pub fn shard_merge(data: &[u8]) -> Result<(), String> {
    let d = scratch("merge");
    let parts = split(data, SHARD_FILES.len());
    let mut inputs = Vec::new();
    for (name, part) in SHARD_FILES.iter().zip(parts) {
        std::fs::write(d.join(name), part).expect("a scratch file");
        inputs.push(d.join(name));
    }
    crate::merge::merge(&d.join("merged.exr"), &inputs)
        .map(drop)
        .map_err(|e| format!("{e:#}"))
}

/// The harnesses by target name (the names of `fuzz/fuzz_targets/`).
pub const TARGETS: &[(&str, fn(&[u8]) -> Result<(), String>)] = &[
    ("toml_scene", toml_scene),
    ("mitsuba_scene", mitsuba_scene),
    ("obj", obj),
    ("ply", ply),
    ("serialized", serialized),
    ("maps_file", maps_file),
    ("shard_merge", shard_merge),
];
