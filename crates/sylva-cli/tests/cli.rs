//! Runs the real `sylva` binary and reads back what it writes.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn sylva(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sylva"))
        .args(args)
        .output()
        .expect("runs sylva")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn arbaro(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/data/arbaro-species")
        .join(name)
}

#[test]
fn generate_writes_a_glb_and_a_json_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("aspen.glb");
    let png = dir.path().join("aspen.png");
    let o = out.to_str().unwrap();
    let run = sylva(&[
        "generate",
        "quaking_aspen",
        "--seed",
        "3",
        "-o",
        o,
        "--preview",
        png.to_str().unwrap(),
        "--json",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).expect("one JSON object");
    for key in [
        "species",
        "seed",
        "stems_per_level",
        "leaves",
        "vertices",
        "triangles",
        "height_m",
        "crown_width_m",
        "generate_ms",
        "mesh_ms",
    ] {
        assert!(v.get(key).is_some(), "missing {key} in {v}");
    }
    assert_eq!(v["species"], "Quaking Aspen");
    assert_eq!(v["seed"], 3);
    assert_eq!(v["stems_per_level"][0], 1);
    let (doc, _, _) = gltf::import(&out).expect("valid GLB");
    let tris: usize = doc
        .meshes()
        .flat_map(|m| {
            m.primitives()
                .map(|p| p.indices().unwrap().count() / 3)
                .collect::<Vec<_>>()
        })
        .sum();
    assert_eq!(tris as u64, v["triangles"].as_u64().unwrap());
    // The preview is a real PNG with something drawn in it.
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
}

#[test]
fn same_seed_same_bytes_other_seed_other_tree() {
    let dir = tempfile::tempdir().unwrap();
    let path = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    for (name, seed) in [("a.glb", "9"), ("b.glb", "9"), ("c.glb", "10")] {
        assert!(
            sylva(&[
                "generate",
                "black_tupelo",
                "--seed",
                seed,
                "-o",
                &path(name)
            ])
            .status
            .success()
        );
    }
    let read = |n: &str| std::fs::read(path(n)).unwrap();
    assert_eq!(read("a.glb"), read("b.glb"));
    assert_ne!(read("a.glb"), read("c.glb"));
}

#[test]
fn obj_export_writes_obj_and_mtl() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("oak.obj");
    let run = sylva(&[
        "generate",
        "ca_black_oak",
        "--quality",
        "0.5",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let obj = std::fs::read_to_string(&out).unwrap();
    assert!(obj.contains("mtllib oak.mtl"));
    assert!(dir.path().join("oak.mtl").exists());
    assert!(text(&run.stdout).contains("stems per level"));
}

#[test]
fn arbaro_files_and_parameter_overrides_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.glb");
    let xml = arbaro("sassafras.xml");
    let run = sylva(&[
        "generate",
        xml.to_str().unwrap(),
        "--set",
        "Leaves=0",
        "--levels",
        "2",
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(v["leaves"], 0);
    assert_eq!(v["stems_per_level"].as_array().unwrap().len(), 2);
    // Arbaro's shave-grass has ScaleV > Scale: it loads with a warning.
    let run = sylva(&[
        "generate",
        arbaro("shave-grass.xml").to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stderr).contains("warning") && text(&run.stderr).contains("ScaleV"));
}

#[test]
fn species_list_and_show() {
    let run = sylva(&["species", "list"]);
    assert!(run.status.success());
    let list = text(&run.stdout);
    for id in [
        "quaking_aspen",
        "black_tupelo",
        "weeping_willow",
        "ca_black_oak",
    ] {
        assert!(list.contains(id), "{list}");
    }
    let run = sylva(&["species", "show", "black_tupelo"]);
    let show = text(&run.stdout);
    assert!(run.status.success());
    assert!(
        show.lines()
            .any(|l| l.starts_with("1DownAngleV") && l.contains("-40") && l.contains("deg")),
        "{show}"
    );
    assert!(show.contains("AttractionUp"));
    // --toml prints a file that loads back to the same species.
    let run = sylva(&["species", "show", "weeping_willow", "--toml"]);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("w.toml");
    std::fs::write(&file, &run.stdout).unwrap();
    let out = dir.path().join("w.glb");
    let made = sylva(&[
        "generate",
        file.to_str().unwrap(),
        "--levels",
        "2",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(made.status.success(), "{}", text(&made.stderr));
}

/// Runs a generation that must fail: non-zero exit, a message containing every `needle`, no file.
fn fails(args: &[&str], needles: &[&str], dir: &Path) {
    let out = dir.join("bad.glb");
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["-o", out.to_str().unwrap()]);
    let run = sylva(&all);
    let err = text(&run.stderr);
    assert!(!run.status.success(), "{args:?} should fail");
    assert!(err.starts_with("sylva: "), "{err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: `{n}` not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists(), "{args:?} left a file");
    let leftovers: Vec<_> = std::fs::read_dir(dir).unwrap().collect();
    assert!(leftovers.iter().all(|e| {
        !e.as_ref()
            .unwrap()
            .file_name()
            .to_string_lossy()
            .ends_with(".tmp")
    }));
}

#[test]
fn bad_input_gives_clear_errors_and_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let write = |name: &str, body: &str| {
        let p = d.join(name);
        std::fs::write(&p, body).unwrap();
        p.to_str().unwrap().to_string()
    };
    let malformed = write("broken.toml", "[params\nShape = 7\n");
    fails(&["generate", &malformed], &["broken.toml", "TOML"], d);
    let out_of_range = write(
        "range.toml",
        "[species]\nname = \"r\"\n[params]\nShape = 7\n1DownAngle = 240\n",
    );
    fails(
        &["generate", &out_of_range],
        &["1DownAngle", "240", "-180..180", "line 5"],
        d,
    );
    let negative = write("neg.toml", "[params]\nScale = 5\nScaleV = 6\n");
    fails(&["generate", &negative], &["ScaleV", "Scale"], d);
    let levels = write("levels.toml", "[params]\nLevels = 50\n");
    fails(&["generate", &levels], &["Levels", "50", "1..9"], d);
    let bad_xml = write(
        "bad.xml",
        "<arbaro><species name='x'><param name='Shape' value='7'></arbaro>",
    );
    fails(&["generate", &bad_xml], &["bad.xml", "XML"], d);
    let unknown_xml = write(
        "unknown.xml",
        "<arbaro><species name='x'>\n<param name='Bogus' value='7'/></species></arbaro>",
    );
    fails(&["generate", &unknown_xml], &["Bogus", "line 2"], d);
    fails(
        &["generate", "quaking_aspen", "--set", "1Branches=1000000000"],
        &["1Branches", "1000000000"],
        d,
    );
    fails(
        &[
            "generate",
            "quaking_aspen",
            "--set",
            "2Branches=90000",
            "--set",
            "3Branches=0",
        ],
        &["budget", "--max-triangles"],
        d,
    );
    fails(
        &["generate", "quaking_aspen", "--max-triangles", "1000"],
        &["budget"],
        d,
    );
    fails(
        &["generate", "no_such_tree"],
        &["no_such_tree", "species list"],
        d,
    );
    fails(
        &["generate", "quaking_aspen", "--set", "Shape"],
        &["NAME=VALUE"],
        d,
    );
    fails(
        &["generate", "quaking_aspen", "--quality", "0"],
        &["quality"],
        d,
    );
    // An unknown output format fails before any work.
    let run = sylva(&[
        "generate",
        "quaking_aspen",
        "-o",
        d.join("x.fbx").to_str().unwrap(),
    ]);
    assert!(!run.status.success() && text(&run.stderr).contains(".glb or .obj"));
}

fn png_size(path: &Path) -> (u32, u32) {
    let img = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    (img.width(), img.height())
}

#[test]
fn render_species_glb_turntable_and_wind_frames() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    let s = |path: &PathBuf| path.to_str().unwrap().to_string();
    let run = sylva(&[
        "render",
        "queen_palm",
        "--size",
        "320x240",
        "--view",
        "iso",
        "-o",
        &s(&p("palm.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(png_size(&p("palm.png")), (320, 240));
    // A GLB written by generate renders too.
    assert!(
        sylva(&["generate", "saguaro", "-o", &s(&p("cactus.glb"))])
            .status
            .success()
    );
    let run = sylva(&[
        "render",
        &s(&p("cactus.glb")),
        "--size",
        "200x200",
        "-o",
        &s(&p("cactus.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // Turntable: 4 views on one 2x2 sheet.
    let run = sylva(&[
        "render",
        "hazel",
        "--turntable",
        "4",
        "--size",
        "100x80",
        "-o",
        &s(&p("sheet.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(png_size(&p("sheet.png")), (200, 160));
    // Wind animation: numbered frames that differ.
    let run = sylva(&[
        "render",
        "weeping_birch",
        "--wind",
        "8",
        "--gust",
        "4",
        "--frames",
        "3",
        "--fps",
        "4",
        "--size",
        "120x120",
        "--bare",
        "-o",
        &s(&p("sway.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let frames: Vec<Vec<u8>> = (0..3)
        .map(|i| std::fs::read(p(&format!("sway-{i:04}.png"))).unwrap())
        .collect();
    assert_ne!(frames[0], frames[2], "the tree moves between frames");
    // Levels as a design aid: the trunk alone.
    let run = sylva(&[
        "render",
        "black_tupelo",
        "--levels",
        "1",
        "--size",
        "100x100",
        "-o",
        &s(&p("trunk.png")),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
}

#[test]
fn render_rejects_bad_requests_without_writing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let o = out.to_str().unwrap();
    for (args, needle) in [
        (
            vec!["render", "quaking_aspen", "--size", "9x9", "-o", o],
            "16..8192",
        ),
        (
            vec!["render", "quaking_aspen", "--size", "big", "-o", o],
            "WIDTHxHEIGHT",
        ),
        (vec!["render", "quaking_aspen", "-o", "x.jpg"], "PNG"),
        (
            vec!["render", "quaking_aspen", "--turntable", "0", "-o", o],
            "at least 1",
        ),
        (vec!["render", "missing.glb", "-o", o], "missing.glb"),
    ] {
        let run = sylva(&args);
        let err = text(&run.stderr);
        assert!(
            !run.status.success() && err.contains(needle),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
    assert!(!out.exists());
}

/// An X server for the viewer's window, stopped when dropped.
struct Xvfb(std::process::Child, String);

impl Xvfb {
    fn start() -> Option<Self> {
        // One display per test: tests of one process run in parallel. Displays whose lock file
        // or socket is left from an X server that was killed are skipped, and a server that
        // exits at once (its display taken after all) makes way for the next number.
        static NEXT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
        for _ in 0..32 {
            let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let number = 90 + (std::process::id() % 400) * 8 + n;
            let socket = format!("/tmp/.X11-unix/X{number}");
            if Path::new(&format!("/tmp/.X{number}-lock")).exists() || Path::new(&socket).exists() {
                continue;
            }
            let display = format!(":{number}");
            let mut child = Command::new("Xvfb")
                .args([
                    display.as_str(),
                    "-screen",
                    "0",
                    "1280x1024x24",
                    "-nolisten",
                    "tcp",
                ])
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .spawn()
                .ok()?;
            for _ in 0..100 {
                if !matches!(child.try_wait(), Ok(None)) {
                    break;
                }
                if Path::new(&socket).exists() {
                    return Some(Self(child, display));
                }
                std::thread::sleep(std::time::Duration::from_millis(50));
            }
            let _ = child.kill();
            let _ = child.wait();
        }
        None
    }

    /// Runs a viewer self-test on this display (`args` end with `--self-test`, given `dir`)
    /// and reads the report it wrote there.
    fn self_test(&self, args: &[&str], dir: &Path, report: &str) -> serde_json::Value {
        let run = Command::new(env!("CARGO_BIN_EXE_sylva"))
            .args(args)
            .args(["--self-test", dir.to_str().unwrap()])
            .env("DISPLAY", &self.1)
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        assert!(run.status.success(), "{}", text(&run.stderr));
        serde_json::from_slice(
            &std::fs::read(dir.join(report)).expect("the viewer wrote its report"),
        )
        .unwrap()
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn viewer_starts_shows_a_tree_and_regenerates_on_an_edit() {
    let Some(x) = Xvfb::start() else {
        // CI installs Xvfb (.ci/run), so there this test always runs.
        assert!(
            std::env::var_os("CI").is_none(),
            "Xvfb is needed for the viewer test in CI"
        );
        eprintln!("skipping the viewer test: no Xvfb here (apt-get install xvfb)");
        return;
    };
    // Kept after the run so the screenshots can be looked at.
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("viewer-self-test");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let report = x.self_test(&["view", "black_tupelo"], &dir, "viewer.json");
    assert!(report["generations"].as_u64().unwrap() >= 2, "{report}");
    let tris = report["triangles"].as_array().unwrap();
    assert_ne!(tris[0], tris[1], "the edit changed the tree: {report}");
    // With the wind on, the tree is re-formed again and again (the animation is live).
    assert!(
        report["wind_generations"].as_u64().unwrap() >= 3,
        "{report}"
    );
    for n in [1, 2] {
        let img = image::open(dir.join(format!("viewer-{n}.png")))
            .unwrap()
            .to_rgb8();
        // The 3-D view (right of the panel) shows a tree: plenty of leaf-green pixels.
        let green = img
            .enumerate_pixels()
            .filter(|(x, _, p)| {
                *x > img.width() / 2
                    && p[1] as f32 > p[0] as f32 * 1.15
                    && p[1] as f32 > p[2] as f32 * 1.1
            })
            .count();
        assert!(green > 2000, "screenshot {n}: {green} green pixels");
    }
    println!("viewer screenshots: {}", dir.display());
}

#[test]
fn forest_writes_shared_variants_as_instances() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("forest.glb");
    let run = sylva(&[
        "forest",
        "--species",
        "quaking_aspen,hazel",
        "--count",
        "25",
        "--area",
        "40x30",
        "--variants",
        "2",
        "--quality",
        "0.3",
        "--seed",
        "5",
        "-o",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let v: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(v["trees"], 25);
    let variants = v["variants"].as_u64().unwrap();
    assert!((2..=4).contains(&variants), "{v}");
    let (doc, _, _) = gltf::import(&out).expect("valid GLB");
    assert_eq!(
        doc.meshes().count() as u64,
        variants,
        "one mesh per variant"
    );
    let nodes: Vec<_> = doc.nodes().collect();
    assert_eq!(nodes.len(), 25, "one node per tree");
    for n in &nodes {
        let (t, _, s) = n.transform().decomposed();
        // Y up: trees stand on the ground (y = 0) inside the plot.
        assert!(
            t[1].abs() < 1e-6 && t[0].abs() <= 20.0 && t[2].abs() <= 15.0,
            "{t:?}"
        );
        assert!((0.85..=1.15).contains(&s[0]));
    }
    for (args, needle) in [
        (
            vec![
                "forest",
                "--species",
                "quaking_aspen",
                "--count",
                "0",
                "-o",
                "f.glb",
            ],
            "--count",
        ),
        (
            vec![
                "forest",
                "--species",
                "quaking_aspen",
                "--area",
                "big",
                "-o",
                "f.glb",
            ],
            "WIDTHxDEPTH",
        ),
        (
            vec!["forest", "--species", "no_such_tree", "-o", "f.glb"],
            "no_such_tree",
        ),
    ] {
        let run = sylva(&args);
        assert!(
            !run.status.success() && text(&run.stderr).contains(needle),
            "{args:?}: {}",
            text(&run.stderr)
        );
    }
}

/// The JSON chunk of a GLB file.
fn glb_json(path: &Path) -> serde_json::Value {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&bytes[20..20 + len]).unwrap()
}

#[test]
fn lod_chain_glb_has_msft_lod_levels_and_a_baked_impostor() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("aspen-lod.glb");
    let run = sylva(&[
        "generate",
        "quaking_aspen",
        "--quality",
        "0.4",
        "--lod-chain",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // A real reader loads it, atlas included.
    let (doc, _, images) = gltf::import(&out).expect("valid GLB");
    assert_eq!(images.len(), 1, "one impostor atlas");
    let atlas = &images[0];
    assert_eq!(atlas.format, gltf::image::Format::R8G8B8A8);
    let alphas: Vec<u8> = atlas.pixels.chunks(4).map(|p| p[3]).collect();
    let clear = alphas.iter().filter(|&&a| a == 0).count();
    let solid = alphas.iter().filter(|&&a| a == 255).count();
    assert!(
        clear > alphas.len() / 5 && solid > alphas.len() / 20,
        "the atlas has transparent background ({clear}) and opaque tree ({solid}) pixels"
    );
    let triangles = |name: &str| {
        let node = doc.nodes().find(|n| n.name() == Some(name)).unwrap();
        node.mesh()
            .unwrap()
            .primitives()
            .map(|p| p.indices().unwrap().count() / 3)
            .sum::<usize>()
    };
    let counts: Vec<usize> = (0..4)
        .map(|k| triangles(&format!("Quaking_Aspen_LOD{k}")))
        .collect();
    assert!(
        counts.windows(2).all(|w| w[1] < w[0]) && counts[3] == 16,
        "{counts:?}"
    );
    // The scene shows LOD0, which lists the others and their screen coverages.
    let json = glb_json(&out);
    assert!(
        json["extensionsUsed"]
            .as_array()
            .unwrap()
            .contains(&serde_json::json!("MSFT_lod"))
    );
    let root = json["scenes"][0]["nodes"][0].as_u64().unwrap() as usize;
    let node = &json["nodes"][root];
    assert_eq!(node["name"], "Quaking_Aspen_LOD0");
    let ids = node["extensions"]["MSFT_lod"]["ids"].as_array().unwrap();
    assert_eq!(ids.len(), 3);
    for (k, id) in ids.iter().enumerate() {
        let n = &json["nodes"][id.as_u64().unwrap() as usize];
        assert_eq!(n["name"], format!("Quaking_Aspen_LOD{}", k + 1));
    }
    let coverage: Vec<f64> = node["extras"]["MSFT_screencoverage"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(coverage.len(), 4);
    assert!(coverage.windows(2).all(|w| w[1] < w[0]), "{coverage:?}");
    // OBJ has no LOD chains.
    let obj = dir.path().join("t.obj");
    let run = sylva(&[
        "generate",
        "quaking_aspen",
        "--lod-chain",
        "-o",
        obj.to_str().unwrap(),
    ]);
    assert!(!run.status.success() && text(&run.stderr).contains("--lod-chain"));
    assert!(!obj.exists());
}

#[test]
fn forest_file_renders_with_and_without_lod_side_by_side() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("grove.toml");
    std::fs::write(
        &file,
        "[forest]\nspecies = [\"quaking_aspen\", \"hazel\"]\ncount = 12\narea = [40, 40]\nvariants = 1\nquality = 0.3\n",
    )
    .unwrap();
    let png = dir.path().join("grove.png");
    let run = sylva(&[
        "render",
        file.to_str().unwrap(),
        "--lod",
        "compare",
        "--range",
        "400",
        "--size",
        "200x150",
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (w, h) = png_size(&png);
    assert_eq!(w, 2 * 200 + 8, "two pictures side by side");
    assert!(h > 150, "with a caption band");
    let out = text(&run.stdout);
    let primitives = |label: &str| -> usize {
        let line = out.lines().find(|l| l.starts_with(label)).unwrap();
        let inner = line.split('(').nth(1).unwrap().split(' ').next().unwrap();
        inner.replace(',', "").parse().unwrap()
    };
    let (with, without) = (primitives("with LOD:"), primitives("without LOD:"));
    assert!(
        with * 5 < without,
        "LOD draws {with} primitives, full detail {without}"
    );
    // Bad requests name what is wrong and write nothing.
    let bad = dir.path().join("bad.png");
    let unknown = dir.path().join("unknown.toml");
    std::fs::write(&unknown, "[forest]\nspecies = [\"no_such_tree\"]\n").unwrap();
    let f = file.to_str().unwrap();
    for (args, needles) in [
        (vec!["render", f, "--fov", "0"], vec!["--fov 0", "1..170"]),
        (vec!["render", f, "--range", "-5"], vec!["--range -5"]),
        (
            vec!["render", f, "--eye", "1,2", "--target", "0,0,0"],
            vec!["--eye", "three numbers"],
        ),
        (vec!["render", f, "--turntable", "3"], vec!["--turntable"]),
        (
            vec!["render", unknown.to_str().unwrap()],
            vec!["unknown.toml", "no_such_tree"],
        ),
    ] {
        let mut all = args.clone();
        all.extend(["-o", bad.to_str().unwrap()]);
        let run = sylva(&all);
        let err = text(&run.stderr);
        assert!(!run.status.success(), "{args:?} should fail");
        for n in needles {
            assert!(err.contains(n), "{args:?}: `{n}` not in {err}");
        }
        assert!(
            !err.contains("panicked") && !bad.exists(),
            "{args:?}: {err}"
        );
    }
    // The GLB of the same forest file.
    let glb = dir.path().join("grove.glb");
    let run = sylva(&[
        "forest",
        file.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (doc, _, _) = gltf::import(&glb).expect("valid GLB");
    assert_eq!(doc.nodes().count(), 12);
}

#[test]
fn forest_viewer_flies_and_draws_fewer_primitives_with_lod() {
    let Some(x) = Xvfb::start() else {
        assert!(
            std::env::var_os("CI").is_none(),
            "Xvfb is needed for the viewer test in CI"
        );
        eprintln!("skipping the forest viewer test: no Xvfb here (apt-get install xvfb)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("grove.toml");
    std::fs::write(
        &file,
        "[forest]\nspecies = [\"quaking_aspen\", \"hazel\"]\ncount = 30\narea = [80, 80]\nvariants = 2\nquality = 0.3\n",
    )
    .unwrap();
    let report = x.self_test(
        &["view", file.to_str().unwrap()],
        dir.path(),
        "forest-viewer.json",
    );
    let frames = report["frames"].as_array().unwrap();
    assert_eq!(frames.len(), 3, "{report}");
    let prims = |f: &serde_json::Value| {
        ["triangles", "lines", "points"]
            .iter()
            .map(|k| f[*k].as_u64().unwrap())
            .sum::<u64>()
    };
    assert_eq!(frames[0]["lod"], true);
    assert_eq!(frames[1]["lod"], false);
    assert!(frames.iter().all(|f| f["trees"] == 30), "{report}");
    assert!(
        prims(&frames[0]) < prims(&frames[1]),
        "LOD on draws fewer primitives than off: {report}"
    );
    // Flown up and back over the forest: more trees in view, each further away.
    assert!(
        frames[2]["trees_drawn"].as_u64() >= frames[0]["trees_drawn"].as_u64(),
        "{report}"
    );
    assert!(frames.iter().all(|f| f["frame_ms"].as_f64().unwrap() > 0.0));
}

#[test]
fn grow_writes_a_model_per_age_a_csv_and_a_chart_and_refuses_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plane");
    let run = sylva(&[
        "grow",
        "london_planetree",
        "--from",
        "3",
        "--to",
        "5",
        "--no-pictures",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    for age in ["03", "04", "05"] {
        let (doc, buffers, _) = gltf::import(out.join(format!("PLAC-age-{age}.glb"))).unwrap();
        assert!(doc.meshes().count() >= 1 && !buffers.is_empty());
        // The leaves carry their light class as COLOR_0: at most ten shades, a lit top and a
        // darker inside.
        let mut shades: Vec<u32> = Vec::new();
        for p in doc.meshes().flat_map(|m| m.primitives()) {
            let reader = p.reader(|b| Some(&buffers[b.index()]));
            if let Some(c) = reader.read_colors(0) {
                shades.extend(c.into_rgb_f32().map(|c| (c[1] * 1000.0).round() as u32));
            }
        }
        shades.sort_unstable();
        shades.dedup();
        assert!(
            (3..=10).contains(&shades.len()) && shades[0] < *shades.last().unwrap(),
            "age {age}: leaf shades {shades:?}"
        );
    }
    let csv = std::fs::read_to_string(out.join("PLAC.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 4, "{csv}");
    assert!(lines[0].starts_with("age,height_model_m,height_measured_m"));
    // Modelled height within 5% of the equation at every age written.
    for line in &lines[1..] {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!((v[1] / v[2] - 1.0).abs() < 0.05, "{line}");
    }
    let chart = image::open(out.join("PLAC-chart.png")).unwrap();
    assert_eq!((chart.width(), chart.height()), (1500, 900));

    let bad = dir.path().join("bad");
    let run = sylva(&["grow", "plane", "-o", bad.to_str().unwrap()]);
    assert!(!run.status.success());
    let err = text(&run.stderr);
    assert!(err.contains("`plane`") && err.contains("PLAC"), "{err}");
    let run = sylva(&[
        "grow",
        "PLAC",
        "--region",
        "Mars",
        "-o",
        bad.to_str().unwrap(),
    ]);
    assert!(
        text(&run.stderr).contains("InlVal"),
        "{}",
        text(&run.stderr)
    );
    let run = sylva(&[
        "grow",
        "PLAC",
        "--from",
        "9",
        "--to",
        "3",
        "-o",
        bad.to_str().unwrap(),
    ]);
    assert!(!run.status.success() && text(&run.stderr).contains("--from 9"));
    assert!(!bad.exists(), "no output folder for refused input");
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let run = sylva(&["grow", "PLAC", "-o", file.to_str().unwrap()]);
    let err = text(&run.stderr);
    assert!(
        !run.status.success() && err.contains("a-file") && err.contains("folder"),
        "{err}"
    );
}

#[test]
fn growth_viewer_shows_ages_side_by_side_and_plays() {
    let Some(x) = Xvfb::start() else {
        assert!(
            std::env::var_os("CI").is_none(),
            "Xvfb is needed for the viewer test in CI"
        );
        eprintln!("skipping the growth viewer test: no Xvfb here (apt-get install xvfb)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "grow",
        "PLAC",
        "--compare",
        "MAGR",
        "--from",
        "2",
        "--to",
        "8",
        "--step",
        "2",
        "--view",
    ];
    let report = x.self_test(&args, dir.path(), "grow-viewer.json");
    // The first, middle and last ages were shown; the trees grow between them.
    let shown = report["shown"].as_array().unwrap();
    let ages: Vec<f64> = shown.iter().map(|s| s["age"].as_f64().unwrap()).collect();
    assert_eq!(ages, [2.0, 4.0, 8.0], "{report}");
    let triangles: Vec<u64> = shown
        .iter()
        .map(|s| s["triangles"].as_u64().unwrap())
        .collect();
    assert!(
        triangles[0] < triangles[1] && triangles[1] < triangles[2],
        "{report}"
    );
    // Play ran from the first age to the last.
    assert_eq!(report["played_to"].as_f64(), Some(8.0), "{report}");
    // Each picture is the window: the young trees fill less of the sky than the old.
    let green = |n: usize| {
        let p = image::open(dir.path().join(format!("grow-viewer-{n}.png")))
            .unwrap()
            .to_rgb8();
        p.pixels()
            .filter(|q| q[1] as i32 > q[0] as i32 + 15 && q[1] as i32 > q[2] as i32 + 15)
            .count()
    };
    assert!(green(0) < green(2), "foliage grows with age");
}

fn profiles(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../profiles")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// Counts `P` and `L` lines of a vector file.
fn pen_moves(path: &Path) -> (usize, usize) {
    let v = std::fs::read_to_string(path).unwrap();
    let count = |c| v.lines().filter(|l| l.starts_with(c)).count();
    assert_eq!(
        count('P') + count('L'),
        v.lines().count(),
        "only P and L lines"
    );
    (count('P'), count('L'))
}

/// Dark pixels of a PNG written by a drawing.
fn inked(path: &Path) -> usize {
    let img = image::open(path).unwrap().to_rgb8();
    img.pixels()
        .filter(|p| p.0.iter().any(|&c| c < 160))
        .count()
}

#[test]
fn fractal_tree_writes_vector_file_drawings_and_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n);
    let run = sylva(&[
        "fractal",
        "--theta1",
        "-35",
        "--theta2",
        "10",
        "--r1",
        "0.73",
        "--r2",
        "0.83",
        "--depth",
        "12",
        "-o",
        p("out.glb").to_str().unwrap(),
        "-o",
        p("out.svg").to_str().unwrap(),
        "-o",
        p("out.png").to_str().unwrap(),
        "-o",
        p("out.vec").to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout).contains("8191 segments, 4096 tips"),
        "{}",
        text(&run.stdout)
    );
    // One `L` per segment; a `P` wherever a segment does not start where the last one ended.
    let (moves, draws) = pen_moves(&p("out.vec"));
    assert_eq!(draws, 8191);
    assert!(moves > 1000 && moves < 8191, "{moves}");
    let (doc, _, _) = gltf::import(p("out.glb")).expect("valid GLB");
    assert_eq!(doc.meshes().count(), 1);
    assert!(inked(&p("out.png")) > 20_000);
    let svg = std::fs::read_to_string(p("out.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("front view"));

    // The same tree drawn from its vector file looks the same from the top.
    let top_a = p("a.png");
    let run = sylva(&[
        "fractal",
        "--depth",
        "12",
        "--view",
        "top",
        "-o",
        top_a.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let top_b = p("b.png");
    let run = sylva(&[
        "draw",
        p("out.vec").to_str().unwrap(),
        "--view",
        "top",
        "-o",
        top_b.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (a, b) = (inked(&top_a) as f64, inked(&top_b) as f64);
    // The vector file has no widths, so its strokes are hairlines: less ink, same figure.
    assert!(b > 0.2 * a && b < a, "{a} {b}");
}

#[test]
fn whisk_and_stick_trees_from_drawn_profiles() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_string_lossy().into_owned();
    let run = sylva(&[
        "whisk",
        "--profile",
        &profiles("round.csv"),
        "--ribs",
        "8",
        "--rings",
        "2",
        "--spokes",
        "3",
        "-o",
        &p("w.vec"),
        "-o",
        &p("w.glb"),
        "-o",
        &p("w.png"),
        "--view",
        "perspective",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("8 ribs, 2 rings, 3 spokes per rib"));
    // Trunk 1 line, 8 ribs of 9 lines, 2 rings of 32, 8×3 spokes of 1.
    let (_, draws) = pen_moves(Path::new(&p("w.vec")));
    assert_eq!(draws, 1 + 8 * 9 + 2 * 32 + 24);
    gltf::import(p("w.glb")).expect("valid GLB");
    assert!(inked(Path::new(&p("w.png"))) > 5_000);
    // Density 3 is Nagel's 12 ribs; an SVG profile scaled to 12 m.
    let run = sylva(&[
        "whisk",
        "--profile",
        &profiles("vase.svg"),
        "--height",
        "12",
        "--density",
        "3",
        "-o",
        &p("v.vec"),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("12 ribs") && text(&run.stdout).contains("12.0"));
    let run = sylva(&[
        "stick",
        "--branches",
        &profiles("sticks.csv"),
        "--ribs",
        "6",
        "-o",
        &p("s.glb"),
        "-o",
        &p("s.vec"),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("4 branches x 6 ribs"));
    let (_, draws) = pen_moves(Path::new(&p("s.vec")));
    assert_eq!(draws, 1 + 6 * (3 + 3 + 3 + 2));
}

#[test]
fn draw_makes_every_view_of_a_species() {
    let dir = tempfile::tempdir().unwrap();
    let mut sizes = Vec::new();
    for view in ["front", "side", "top", "perspective", "overlay"] {
        let png = dir.path().join(format!("{view}.png"));
        let run = sylva(&[
            "draw",
            "quaking_aspen",
            "--no-leaves",
            "--view",
            view,
            "--size",
            "320x400",
            "-o",
            png.to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{view}: {}", text(&run.stderr));
        assert_eq!(png_size(&png), (320, 400));
        sizes.push(inked(&png));
    }
    assert!(sizes.iter().all(|&n| n > 2_000), "{sizes:?}");
    // The overlay holds two elevations: more ink than either.
    assert!(sizes[4] > sizes[0] && sizes[4] > sizes[1], "{sizes:?}");
}

/// Writes an input file `in-NAME` (which [`refuses`] does not count as output); its path.
fn scratch_input(dir: &Path, name: &str, body: &str) -> String {
    let path = dir.join(format!("in-{name}"));
    std::fs::write(&path, body).unwrap();
    path.to_string_lossy().into_owned()
}

/// Path of an output file in `dir`, as text.
fn scratch(dir: &Path, name: &str) -> String {
    dir.join(name).to_string_lossy().into_owned()
}

/// A command that must fail: non-zero exit, every needle in the message, no file, no temp file.
fn refuses(args: &[&str], needles: &[&str], dir: &Path) {
    let run = sylva(args);
    let err = text(&run.stderr);
    assert!(!run.status.success(), "{args:?} should fail");
    for n in needles {
        assert!(err.contains(n), "{args:?}: `{n}` not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    let files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with("in-"))
        .collect();
    assert!(files.is_empty(), "{args:?} left {files:?}");
}

#[test]
fn nagel_commands_refuse_bad_input_with_line_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (input, out) = (
        |n: &str, body: &str| scratch_input(d, n, body),
        |n: &str| scratch(d, n),
    );
    let bad_csv = input("p.csv", "radius,height\n0,2\n1,3\n2,abc\n");
    refuses(
        &[
            "whisk",
            "--profile",
            &bad_csv,
            "-o",
            &out("a.vec"),
            "-o",
            &out("a.glb"),
        ],
        &["in-p.csv, line 4", "expected numbers"],
        d,
    );
    let bad_svg = input(
        "p.svg",
        "<svg viewBox=\"0 0 10 10\">\n\n<polyline points=\"5,5 2,2\"/></svg>",
    );
    refuses(
        &["whisk", "--profile", &bad_svg, "-o", &out("a.svg")],
        &["in-p.svg, line 3", "left of the trunk"],
        d,
    );
    let bad_vec = input("t.vec", "P 0,0,0\nL 1,1,1\nL 2,2\n");
    refuses(
        &["draw", &bad_vec, "-o", &out("a.png")],
        &["in-t.vec, line 3", "three coordinates"],
        d,
    );
    let vec_file = input("ok.vec", "P 0,0,0\nL 1,1,1\n");
    refuses(
        &["draw", &vec_file, "-o", &out("a.glb")],
        &["no stem radii"],
        d,
    );
    refuses(
        &[
            "whisk",
            "--profile",
            &profiles("round.csv"),
            "--density",
            "7",
            "-o",
            &out("a.vec"),
        ],
        &["--density 7", "1 (least dense) to 5"],
        d,
    );
    refuses(
        &["fractal", "--depth", "30", "-o", &out("a.vec")],
        &["budget", "--max-segments"],
        d,
    );
    refuses(
        &["fractal", "--r1", "-1", "-o", &out("a.vec")],
        &["r1", "0..1.5"],
        d,
    );
    refuses(
        &["fractal", "-o", &out("a.dxf")],
        &["unknown format", ".vec"],
        d,
    );
    refuses(
        &["stick", "--branches", &bad_csv, "-o", &out("a.vec")],
        &["expected 3 values"],
        d,
    );
    refuses(
        &["fractal", "--size", "10x10", "-o", &out("a.png")],
        &["16..16384"],
        d,
    );
}

#[test]
fn lobes_grows_the_three_species_saves_and_reloads_tree_files() {
    let dir = tempfile::tempdir().unwrap();
    let p = |n: &str| dir.path().join(n).to_string_lossy().into_owned();
    for species in ["black_oak", "balsam_fir", "weeping_cherry"] {
        let run = sylva(&[
            "lobes",
            species,
            "--seed",
            "4",
            "-o",
            &p(&format!("{species}.glb")),
            "-o",
            &p(&format!("{species}.tree")),
            "-o",
            &p(&format!("{species}.vec")),
        ]);
        assert!(run.status.success(), "{species}: {}", text(&run.stderr));
        let (doc, _, _) = gltf::import(p(&format!("{species}.glb"))).expect("valid GLB");
        assert_eq!(
            doc.meshes().next().unwrap().primitives().count(),
            2,
            "bark and leaves"
        );
        // The .tree file regrows the same tree.
        let again = p(&format!("{species}-again.vec"));
        let run = sylva(&["lobes", &p(&format!("{species}.tree")), "-o", &again]);
        assert!(run.status.success(), "{}", text(&run.stderr));
        assert!(text(&run.stdout).contains("from the .tree file"));
        assert_eq!(
            std::fs::read(p(&format!("{species}.vec"))).unwrap(),
            std::fs::read(&again).unwrap(),
            "{species}"
        );
    }
    // The appendix's own file, Y up in room coordinates, grows as a two-lobed cherry.
    let appendix = p("appendix.tree");
    std::fs::write(
        &appendix,
        "Cherry Tree\n100\n#BRANCHES\n0 -1 1.110022 -1.582516 4.728205 1.14952 -0.8700994 4.896452 1\n\
         1 0 1.14952 -0.8700994 4.896452 1.800362 -0.3780254 4.764441 1\n\
         2 0 1.14952 -0.8700994 4.896452 0.7252637 -0.7159721 4.99926 1\n\
         3 2 0.7252637 -0.7159721 4.99926 0.5519101 0.02624928 5.070594 1\n\
         #LEAF LOBES\n2.307282 0.5082518 4.534246 1\n0.4439276 1.201943 4.939856 1\n",
    )
    .unwrap();
    let run = sylva(&["lobes", &appendix, "-o", &p("appendix.glb")]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("Weeping Cherry Tree (seed 100)"));
    assert!(text(&run.stdout).contains(": 2 lobes"));
    // Lobes of one's own.
    let run = sylva(&[
        "lobes",
        "black_oak",
        "--lobe",
        "0,0,3,1",
        "--lobe",
        "1.5,0,3.5,0.8",
        "-o",
        &p("own.vec"),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("lobes as given: 2 lobes"));
}

#[test]
fn lobes_fit_a_point_cloud() {
    let dir = tempfile::tempdir().unwrap();
    let cloud = dir.path().join("scan.xyz");
    // A trunk 2 m tall and a ball of crown 1.2 m in radius above it, 3 m up.
    let mut body = String::new();
    for i in 0..400 {
        let a = i as f32 * 0.7;
        body.push_str(&format!(
            "{} {} {}\n",
            0.1 * a.cos(),
            0.1 * a.sin(),
            2.0 * i as f32 / 400.0
        ));
    }
    // xorshift64*: plain, seeded, good enough to fill a ball.
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
    };
    let mut n = 0;
    while n < 4000 {
        let (x, y, z) = (next(), next(), next());
        if x * x + y * y + z * z <= 1.0 {
            body.push_str(&format!("{} {} {}\n", 1.2 * x, 1.2 * y, 3.2 + 1.2 * z));
            n += 1;
        }
    }
    std::fs::write(&cloud, body).unwrap();
    let tree = dir.path().join("fit.tree");
    let run = sylva(&[
        "lobes",
        "black_oak",
        "--points",
        cloud.to_str().unwrap(),
        "-o",
        tree.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let out = text(&run.stdout);
    assert!(
        out.contains("fitted to 4400 points") && out.contains("1 lobes"),
        "{out}"
    );
    let saved = std::fs::read_to_string(&tree).unwrap();
    let lobe: Vec<f32> = saved
        .lines()
        .last()
        .unwrap()
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    // Y up in the file: the lobe's centre 3.2 m up becomes its y.
    assert!(
        (lobe[1] - 3.2).abs() < 0.15 && (lobe[3] - 1.2).abs() < 0.15,
        "{saved}"
    );
}

#[test]
fn lobes_refuses_bad_input_with_line_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (input, out) = (
        |n: &str, body: &str| scratch_input(d, n, body),
        |n: &str| scratch(d, n),
    );
    let bad_tree = input(
        "t.tree",
        "Black Oak\n1\n#BRANCHES\n0 -1 0 0 0 0 1\n#LEAF LOBES\n0 2 0 1\n",
    );
    refuses(
        &["lobes", &bad_tree, "-o", &out("a.glb")],
        &["in-t.tree, line 4", "found 7 values"],
        d,
    );
    let odd_type = input("u.tree", "Baobab\n1\n#BRANCHES\n#LEAF LOBES\n0 2 0 1\n");
    refuses(&["lobes", &odd_type, "-o", &out("a.glb")], &["Baobab"], d);
    let bad_ply = input(
        "c.ply",
        "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n1 2 x\n",
    );
    refuses(
        &[
            "lobes",
            "black_oak",
            "--points",
            &bad_ply,
            "-o",
            &out("a.glb"),
        ],
        &["in-c.ply, line 9", "`x`"],
        d,
    );
    let bad_rules = input("r.toml", "[rules]\nname = \"Mine\"\nTrunkAngle = 10\n");
    refuses(
        &["lobes", &bad_rules, "-o", &out("a.glb")],
        &["in-r.toml", "lacks 24 of the 25 rules", "BranchAngle"],
        d,
    );
    refuses(
        &["lobes", "baobab", "-o", &out("a.glb")],
        &["black_oak, balsam_fir"],
        d,
    );
    refuses(
        &["lobes", "black_oak", "--lobe", "0,0,1", "-o", &out("a.glb")],
        &["--lobe 0,0,1", "X,Y,Z,R"],
        d,
    );
    refuses(
        &["lobes", "black_oak", "--scale", "0", "-o", &out("a.tree")],
        &["--scale 0"],
        d,
    );
    refuses(
        &[
            "lobes",
            "black_oak",
            "--tessellation",
            "2",
            "-o",
            &out("a.glb"),
        ],
        &["--tessellation 2", "3..64"],
        d,
    );
}

#[test]
fn model_viewer_shows_a_lobe_tree_glb_from_two_sides() {
    let Some(x) = Xvfb::start() else {
        assert!(
            std::env::var_os("CI").is_none(),
            "Xvfb is needed for the viewer test in CI"
        );
        eprintln!("skipping the model viewer test: no Xvfb here (apt-get install xvfb)");
        return;
    };
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("model-viewer-self-test");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // Two lobes side by side along x: from the front they stand apart, from the side they
    // overlap, so a quarter turn narrows the crown.
    let glb = dir.join("two-lobes.glb");
    let run = sylva(&[
        "lobes",
        "black_oak",
        "--lobe",
        "-1.6,0,3,1",
        "--lobe",
        "1.6,0,3,1",
        "--tessellation",
        "8",
        "-o",
        glb.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let report = x.self_test(&["view", glb.to_str().unwrap()], &dir, "model-viewer.json");
    assert!(report["triangles"].as_u64().unwrap() > 10_000, "{report}");
    assert_eq!(report["azimuth"], 90.0);
    let widths: Vec<u32> = [1, 2]
        .iter()
        .map(|n| {
            let img = image::open(dir.join(format!("model-viewer-{n}.png")))
                .unwrap()
                .to_rgb8();
            // Columns holding leaf-green pixels: the crown's width on screen.
            let green = |x: u32| {
                (0..img.height()).any(|y| {
                    let p = img.get_pixel(x, y);
                    p[1] as f32 > p[0] as f32 * 1.2 && p[1] as f32 > p[2] as f32 * 1.2
                })
            };
            let cols: Vec<u32> = (0..img.width()).filter(|&x| green(x)).collect();
            assert!(cols.len() > 50, "screenshot {n}: no crown");
            cols.last().unwrap() - cols.first().unwrap()
        })
        .collect();
    assert!(
        (widths[1] as f32) < 0.7 * widths[0] as f32,
        "front {} px, side {} px",
        widths[0],
        widths[1]
    );
    println!("model viewer screenshots: {}", dir.display());
}

#[test]
fn draw_grows_a_street_tree_to_an_age_for_plans() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let plan = d.join("plac-10.png");
    let run = sylva(&[
        "draw",
        "PLAC",
        "--age",
        "10",
        "--view",
        "top",
        "--size",
        "400x400",
        "-o",
        plan.to_str().unwrap(),
        "-o",
        &scratch(d, "plac-10.vec"),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // The plan of a ten-year-old plane: a round crown, about as wide as it is deep.
    let img = image::open(&plan).unwrap().to_rgb8();
    let ink: Vec<(u32, u32)> = img
        .enumerate_pixels()
        .filter(|(_, _, p)| p.0.iter().any(|&c| c < 160))
        .map(|(x, y, _)| (x, y))
        .collect();
    let span = |f: fn(&(u32, u32)) -> u32| {
        ink.iter().map(f).max().unwrap() - ink.iter().map(f).min().unwrap()
    };
    let (w, h) = (span(|p| p.0), span(|p| p.1));
    assert!(
        ink.len() > 5_000 && (w as f32 / h as f32 - 1.0).abs() < 0.25,
        "{w} x {h}"
    );
    let (moves, draws) = pen_moves(&d.join("plac-10.vec"));
    assert!(moves > 100 && draws > 1_000);
    let empty = tempfile::tempdir().unwrap();
    let d = empty.path();
    refuses(
        &["draw", "PLAC", "--age", "900", "-o", &scratch(d, "a.png")],
        &["--age 900", "London planetree"],
        d,
    );
    refuses(
        &[
            "draw",
            "PLAC",
            "--age",
            "5",
            "--region",
            "Atlantis",
            "-o",
            &scratch(d, "a.png"),
        ],
        &["Atlantis"],
        d,
    );
}
