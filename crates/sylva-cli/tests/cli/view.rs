//! The windows (`sylva view`, `sylva grow --view`), each run through its self-test under Xvfb.

use crate::*;

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
    assert_eq!(report["season"], serde_json::Value::Null, "{report}");
    // In winter the plane is bare and only the evergreen magnolia keeps its leaves.
    let summer = green(2);
    let mut winter_args = args.to_vec();
    winter_args.extend(["--season", "winter"]);
    let report = x.self_test(&winter_args, dir.path(), "grow-viewer.json");
    assert_eq!(report["season"], "winter", "{report}");
    let winter = green(2);
    assert!(
        winter * 3 < summer * 2 && winter > 0,
        "green pixels at 8 years: {summer} in summer, {winter} in winter"
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
    // A lobe species by name: grown at its natural size and shown in the same window. The fir
    // is a narrow spire: its crown is far taller on screen than it is wide.
    let fir = dir.join("fir");
    std::fs::create_dir_all(&fir).unwrap();
    let report = x.self_test(&["view", "lobes:balsam_fir"], &fir, "model-viewer.json");
    assert!(report["triangles"].as_u64().unwrap() > 100_000, "{report}");
    let img = image::open(fir.join("model-viewer-1.png"))
        .unwrap()
        .to_rgb8();
    let dark_green = |p: &image::Rgb<u8>| p[1] as f32 > p[0] as f32 * 1.3 && p[1] > p[2];
    let (mut lo, mut hi) = ((u32::MAX, u32::MAX), (0, 0));
    for (x, y, p) in img.enumerate_pixels() {
        if dark_green(p) {
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
        }
    }
    assert!(hi.0 > lo.0, "no needles on screen");
    let (w, h) = (hi.0 - lo.0, hi.1 - lo.1);
    assert!(h as f32 > 2.0 * w as f32, "fir crown {w} x {h} px");
}
