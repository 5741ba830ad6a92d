//! The readers' fuzz corpus on stable Rust: every seed of `fuzz/seeds/` and every input a
//! fuzz run found (`fuzz/regressions/`) through the fuzz targets' own harnesses
//! (`footprint_app::fuzz`), and absurd inputs that each protection of the readers refuses
//! with an error naming the file: without the protection they panic, hang or allocate
//! without bound. docs/testing.md, "Fuzzing", has the fuzzing commands.

use footprint_app::fuzz;
use std::path::{Path, PathBuf};

fn fuzz_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz")
}

/// The files of `fuzz/<kind>/<target>/`, sorted (none if the folder does not exist).
fn inputs(kind: &str, target: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(fuzz_dir().join(kind).join(target))
        .map(|d| d.map(|e| e.unwrap().path()).collect())
        .unwrap_or_default();
    files.sort();
    files
}

fn harness(target: &str) -> fn(&[u8]) -> Result<(), String> {
    fuzz::TARGETS
        .iter()
        .find(|(n, _)| *n == target)
        .unwrap_or_else(|| panic!("no harness {target}"))
        .1
}

/// The file names a target's errors may name.
fn file_names(target: &str) -> &'static [&'static str] {
    match target {
        "toml_scene" => &["scene.toml", "mesh.obj", "mesh.mtl"],
        "mitsuba_scene" => fuzz::XML_FILES,
        "obj" => &["mesh.obj", "mesh.mtl", "texture.png", "scene.toml"],
        "ply" => &[fuzz::PLY_FILE],
        "serialized" => &[fuzz::SERIALIZED_FILE],
        "maps_file" => &["maps.fpm"],
        "shard_merge" => &[
            "shard0.exr",
            "shard1.exr",
            "shard2.exr",
            "shard3.exr",
            "merged.exr",
        ],
        _ => unreachable!(),
    }
}

fn assert_names_a_file(target: &str, what: &str, err: &str) {
    assert!(
        file_names(target).iter().any(|f| err.contains(f))
            // A merge's errors about the set of shards name no one file.
            || (target == "shard_merge" && err.contains("missing shard")),
        "{target}: {what}: the error names no file: {err}"
    );
}

/// Every seed is a good input: it reads without error (so the harness reaches the reader's
/// depths, and the seeds stay in step with the formats).
#[test]
fn the_seeds_read() {
    let mut count = 0;
    for (target, run) in fuzz::TARGETS {
        let seeds = inputs("seeds", target);
        assert!(!seeds.is_empty(), "{target} has no seeds");
        for seed in seeds {
            let data = std::fs::read(&seed).unwrap();
            if let Err(e) = run(&data) {
                panic!("{}: {e}", seed.display());
            }
            count += 1;
        }
    }
    assert!(count >= 15, "{count} seeds");
}

/// Every input a fuzz run found a fault with gives an error naming a file, and no panic.
#[test]
fn the_found_inputs_give_errors() {
    for (target, run) in fuzz::TARGETS {
        for input in inputs("regressions", target) {
            let data = std::fs::read(&input).unwrap();
            match run(&data) {
                Ok(()) => {}
                Err(e) => assert_names_a_file(target, &input.display().to_string(), &e),
            }
        }
    }
}

/// The seeds cut short at a few places: no panic, and an error names a file.
#[test]
fn truncated_seeds_give_errors() {
    for (target, run) in fuzz::TARGETS {
        for seed in inputs("seeds", target) {
            let data = std::fs::read(&seed).unwrap();
            for cut in [1, 7, data.len() / 3, data.len() / 2, data.len() - 1] {
                if let Err(e) = run(&data[..cut.min(data.len())]) {
                    assert_names_a_file(target, &format!("{} cut at {cut}", seed.display()), &e);
                }
            }
        }
    }
}

fn expect_err(target: &str, data: &[u8], needles: &[&str]) {
    let err = harness(target)(data).expect_err("an absurd input is refused");
    assert_names_a_file(target, "absurd input", &err);
    for n in needles {
        assert!(
            err.contains(n),
            "{target}: the error should say '{n}': {err}"
        );
    }
}

const CAMERA: &str =
    "[camera]\nposition = [0.5, 0.5, -2.0]\nlook_at = [0.5, 0.5, 0.0]\nfov_y = 40.0\n";
const QUAD: &str = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";

fn toml_with_mesh(body: &str, obj: &str) -> Vec<u8> {
    fuzz::join(&[
        format!("{CAMERA}{body}[[mesh]]\nfile = \"mesh.obj\"\n").as_bytes(),
        obj.as_bytes(),
    ])
}

#[test]
fn an_absurd_film_is_refused() {
    expect_err(
        "toml_scene",
        &toml_with_mesh("resolution = [1000000000, 1000000000]\n", QUAD),
        &["scene.toml", "32768"],
    );
}

#[test]
fn non_finite_and_huge_values_are_refused() {
    let r = "resolution = [8, 8]\n";
    expect_err(
        "toml_scene",
        &toml_with_mesh(
            &format!(
                "{r}[[light]]\ntype = \"point\"\nposition = [0, nan, 0]\nintensity = [1, 1, 1]\n"
            ),
            QUAD,
        ),
        &["scene.toml", "light[0].position"],
    );
    expect_err(
        "obj",
        &fuzz::join(&[b"v 0 0 0\nv 1 0 nan\nv 1e39 0 1\nf 1 2 3\n"]),
        &["mesh.obj:2", "not a finite number"],
    );
}

/// Coordinates of 10³⁸ are finite but no scene's: refused at the line or field that holds
/// them, or, made by a transform, for the scene as a whole; an intensity whose power
/// overflows is refused as such (not as "no lights").
#[test]
fn coordinates_of_1e38_are_refused() {
    let r = "resolution = [8, 8]\n";
    let emissive = "mtllib mesh.mtl\nusemtl e\n";
    let mtl = b"newmtl e\nKe 1 1 1\n".as_slice();
    let scene = |body: &str, obj: &str, mtl: &[u8]| {
        fuzz::join(&[
            format!("{CAMERA}{r}{body}[[mesh]]\nfile = \"mesh.obj\"\n").as_bytes(),
            obj.as_bytes(),
            mtl,
        ])
    };
    expect_err(
        "toml_scene",
        &scene(
            "",
            &format!("{emissive}v 0 0 0\nv 1 0 0\nv 1e38 0 1\nf 1 2 3\n"),
            mtl,
        ),
        &["mesh.obj:5", "'1e38' is farther than 1e15"],
    );
    expect_err(
        "toml_scene",
        &toml_with_mesh(
            &format!(
                "{r}[[light]]\ntype = \"point\"\nposition = [0, 3e38, 0]\nintensity = [1, 1, 1]\n"
            ),
            QUAD,
        ),
        &["scene.toml", "light[0].position is farther than 1e15"],
    );
    let quad = format!("{emissive}{QUAD}");
    let moved = |t: &str| {
        fuzz::join(&[
            format!("{CAMERA}{r}[[mesh]]\nfile = \"mesh.obj\"\ntransform = {{ {t} }}\n").as_bytes(),
            quad.as_bytes(),
            mtl,
        ])
    };
    expect_err(
        "toml_scene",
        &moved("translate = [3e38, 0, 0]"),
        &[
            "scene.toml",
            "mesh[0].transform.translate is farther than 1e15",
        ],
    );
    // Vertices at the limit, scaled past it (a triangle of 10¹⁷ m edges would be degenerate:
    // its area overflows).
    let edge = format!("{emissive}v 1e15 0 0\nv 1e15 1e8 0\nv 1e15 0 1e8\nf 1 2 3\n");
    expect_err(
        "toml_scene",
        &fuzz::join(&[
            format!("{CAMERA}{r}[[mesh]]\nfile = \"mesh.obj\"\ntransform = {{ scale = 10 }}\n")
                .as_bytes(),
            edge.as_bytes(),
            mtl,
        ]),
        &["scene.toml", "reaches farther than 1e15 m"],
    );
    expect_err(
        "toml_scene",
        &toml_with_mesh(
            &format!(
                "{r}[[light]]\ntype = \"point\"\nposition = [0, 1, 0]\nintensity = [3e38, 3e38, 3e38]\n"
            ),
            QUAD,
        ),
        &["scene.toml", "power is not a finite number"],
    );
}

/// A maps payload whose particle count says 10^12: refused before anything is allocated.
#[test]
fn a_maps_file_declaring_a_trillion_particles_is_refused() {
    let mut p = Vec::new();
    let key = b"k";
    p.extend_from_slice(&(key.len() as u32).to_le_bytes());
    p.extend_from_slice(key);
    p.push(1); // light pass present
    p.extend_from_slice(&1u64.to_le_bytes()); // paths
    p.extend_from_slice(&[0; 12]); // emitted
    p.extend_from_slice(&0u32.to_le_bytes()); // escaped
    p.extend_from_slice(&0f64.to_le_bytes()); // seconds
    p.extend_from_slice(&u64::MAX.to_le_bytes()); // every particle seeds
    p.extend_from_slice(&0u32.to_le_bytes()); // thinning level
    p.extend_from_slice(&1_000_000_000_000u64.to_le_bytes()); // particles
    let mut input = vec![1];
    input.extend_from_slice(&p);
    expect_err("maps_file", &input, &["maps.fpm", "corrupt"]);
}

/// A maps payload with a particle at NaN: corrupt, though its checksum matches.
#[test]
fn a_maps_file_with_a_nan_particle_is_refused() {
    let mut p = Vec::new();
    p.extend_from_slice(&1u32.to_le_bytes());
    p.push(b'k');
    p.push(1);
    p.extend_from_slice(&1u64.to_le_bytes());
    p.extend_from_slice(&[0; 12]);
    p.extend_from_slice(&0u32.to_le_bytes());
    p.extend_from_slice(&0f64.to_le_bytes());
    p.extend_from_slice(&u64::MAX.to_le_bytes()); // every particle seeds
    p.extend_from_slice(&0u32.to_le_bytes()); // thinning level
    p.extend_from_slice(&1u64.to_le_bytes()); // one particle
    for v in [
        [f32::NAN, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
        [1.0; 3],
    ] {
        for x in v {
            p.extend_from_slice(&x.to_le_bytes());
        }
    }
    p.extend_from_slice(&2u16.to_le_bytes());
    p.push(0);
    p.extend_from_slice(&0u64.to_le_bytes()); // emission points
    p.push(0); // no view pass
    let mut input = vec![1];
    input.extend_from_slice(&p);
    // The same payload with a finite position reads.
    let mut good = input.clone();
    let at = input.len() - 1 - 8 - 3 - 48;
    good[at..at + 4].copy_from_slice(&0f32.to_le_bytes());
    harness("maps_file")(&good).expect("the finite particle reads");
    expect_err("maps_file", &input, &["maps.fpm", "not finite"]);
}

/// XML nested thousands deep: an error at the line where the depth passes the limit, not a
/// stack overflow in the importer's recursive walk.
#[test]
fn deeply_nested_xml_is_refused() {
    let n = 20_000;
    let mut xml = String::from("<scene version=\"3.0.0\">\n");
    for _ in 0..n {
        xml.push_str("<bsdf type=\"twosided\">\n");
    }
    for _ in 0..n {
        xml.push_str("</bsdf>");
    }
    xml.push_str("</scene>\n");
    expect_err(
        "mitsuba_scene",
        xml.as_bytes(),
        &["scene.xml:65:", "nested more than 64 deep"],
    );
}

/// `data`, an EXR, with its text attribute `key` set to `value` (the header's attribute is
/// name, type `string`, a u32 size and the text).
fn set_exr_text(data: &[u8], key: &str, value: &str) -> Vec<u8> {
    let name = format!("{key}\0string\0");
    let at = data
        .windows(name.len())
        .position(|w| w == name.as_bytes())
        .unwrap_or_else(|| panic!("no attribute {key}"))
        + name.len();
    let size = u32::from_le_bytes(data[at..at + 4].try_into().unwrap()) as usize;
    let mut out = data[..at].to_vec();
    out.extend_from_slice(&(value.len() as u32).to_le_bytes());
    out.extend_from_slice(value.as_bytes());
    out.extend_from_slice(&data[at + 4 + size..]);
    out
}

/// A shard whose header says it is one of four billion: refused without a list of four
/// billion places, naming a few of the missing shards.
#[test]
fn a_shard_of_four_billion_is_refused() {
    let seed = std::fs::read(fuzz_dir().join("seeds/shard_merge/cornell-1-shard")).unwrap();
    let data = set_exr_text(&seed, "footprint/shard", "0/4000000000");
    let data = set_exr_text(&data, "footprint/spp", "1");
    expect_err(
        "shard_merge",
        &data,
        &[
            "missing shards 1/4000000000",
            "8/4000000000, and 3999999991 more",
        ],
    );
}

/// A shard whose header says its layer is a billion pixels wide: refused before a sum of a
/// billion squared pixels is allocated.
#[test]
fn a_shard_of_absurd_size_is_refused() {
    let seed = std::fs::read(fuzz_dir().join("seeds/shard_merge/cornell-1-shard")).unwrap();
    // The header's dataWindow: box2i, min (0, 0), max (3, 3) for 4x4 pixels.
    let name = b"dataWindow\0box2i\0\x10\0\0\0";
    let at = seed
        .windows(name.len())
        .position(|w| w == name)
        .expect("a data window")
        + name.len();
    let mut data = seed.clone();
    data[at + 8..at + 12].copy_from_slice(&1_000_000_000i32.to_le_bytes());
    data[at + 12..at + 16].copy_from_slice(&1_000_000_000i32.to_le_bytes());
    expect_err(
        "shard_merge",
        &data,
        &["shard0.exr", "1 to 32768 pixels a side"],
    );
}

/// Hashes are shown cut to 16 characters: a header's or a key's text that is not ASCII is
/// cut at a character, not inside one (a panic before).
#[test]
fn a_hash_that_is_not_ascii_is_shown_without_a_panic() {
    let seed = std::fs::read(fuzz_dir().join("seeds/shard_merge/cornell-2-shards")).unwrap();
    let parts = fuzz::split(&seed, 2);
    let other = set_exr_text(parts[1], "footprint/scene_hash", "aÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈ");
    expect_err(
        "shard_merge",
        &fuzz::join(&[parts[0], &other]),
        &["shard1.exr is a render of another scene"],
    );
    let mut p = Vec::new();
    let key = "scene=aÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈ";
    p.extend_from_slice(&(key.len() as u32).to_le_bytes());
    p.extend_from_slice(key.as_bytes());
    p.extend_from_slice(&[0, 0]);
    // Bit 0: a payload; bit 1: loaded with fuzz::MAPS_KEY, another scene's.
    let mut input = vec![3];
    input.extend_from_slice(&p);
    expect_err(
        "maps_file",
        &input,
        &[
            "maps.fpm was made for another scene",
            "aÈÈÈÈÈÈÈÈÈÈÈÈÈÈÈ there",
        ],
    );
}

/// `data` as a zlib stream of one stored (uncompressed) deflate block (RFC 1950, 1951): a
/// `.serialized` mesh written by hand, with no compressor.
fn zlib_stored(data: &[u8]) -> Vec<u8> {
    assert!(data.len() < 65536);
    let mut out = vec![0x78, 0x01, 0x01];
    let len = data.len() as u16;
    out.extend_from_slice(&len.to_le_bytes());
    out.extend_from_slice(&(!len).to_le_bytes());
    out.extend_from_slice(data);
    let (mut a, mut b) = (1u32, 0u32);
    for &x in data {
        a = (a + x as u32) % 65521;
        b = (b + a) % 65521;
    }
    out.extend_from_slice(&((b << 16) | a).to_be_bytes());
    out
}

/// Mesh files whose counts lie: a PLY whose header promises a billion faces and four billion
/// vertices a face, and `.serialized` meshes that say 2³¹ vertices and 2⁴⁰ triangles, or
/// more vertices than they hold, in files of a few hundred bytes: refused at once, naming the
/// file, with nothing reserved for the counts.
#[test]
fn mesh_files_with_lying_counts_are_refused() {
    let seed = std::fs::read(fuzz_dir().join("seeds/ply/quads-ascii")).unwrap();
    let text = String::from_utf8(seed).unwrap();
    expect_err(
        "ply",
        text.replace("element face 3", "element face 1000000000")
            .as_bytes(),
        &["mesh.ply", "element 'face', record 3 of 1000000000"],
    );
    expect_err(
        "ply",
        text.replace("4 0 1 2 3", "4294967295 0 1 2 3").as_bytes(),
        &["mesh.ply", "'4294967295' is not a uchar"],
    );
    expect_err(
        "ply",
        text.replace("3 0 1 6", "3 0 1 7").as_bytes(),
        &[
            "mesh.ply",
            "face 2 refers to vertex 7, but the file has 7 vertices",
        ],
    );
    // Version 4: flags (single precision, no normals), name, counts, one triangle.
    let mesh = |vertices: u64, triangles: u64| {
        let mut s = 0x1000u32.to_le_bytes().to_vec();
        s.extend_from_slice(b"m\0");
        s.extend_from_slice(&vertices.to_le_bytes());
        s.extend_from_slice(&triangles.to_le_bytes());
        for v in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
            s.extend_from_slice(&v.to_le_bytes());
        }
        for i in [0u32, 1, 2] {
            s.extend_from_slice(&i.to_le_bytes());
        }
        let mut file = vec![0, 0x1c, 0x04, 4, 0];
        file.extend_from_slice(&zlib_stored(&s));
        file
    };
    assert_eq!(harness("serialized")(&mesh(3, 1)), Ok(()));
    expect_err(
        "serialized",
        &mesh(1 << 31, 1 << 40),
        &["mesh.serialized", "more than the"],
    );
    expect_err(
        "serialized",
        &mesh(4, 1),
        &["mesh.serialized", "the data ends within the triangles"],
    );
    // Two vertices said, three written: the third's 1.0 (0x3f800000) is read as an index.
    expect_err(
        "serialized",
        &mesh(2, 1),
        &[
            "mesh.serialized",
            "triangle 0 refers to vertex 1065353216, but the mesh has 2 vertices",
        ],
    );
}
