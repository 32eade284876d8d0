//! A bounded fuzz campaign over every input Sylva reads: species files and `--set` values,
//! Arbaro XML, Fields' rules and `.tree` files, point clouds, drawn profiles, fractal flags,
//! forest files, growth flags, output paths and damaged GLBs. Each case runs the real binary
//! (pictures on the CPU rasteriser, so any machine runs it) and must exit 0, or refuse with a
//! message naming its input, leave nothing behind, and never panic, hang or run away with
//! memory (see `harness::broken`).
//!
//! `SYLVA_FUZZ_CASES` sets the cases per family (default 8; CI runs more) and
//! `SYLVA_FUZZ_SEED` the campaign's seed (default 1): a failure prints the seed and the case.

mod harness;
mod mutate;

use harness::{Case, Rng, broken, run, scratch};
use mutate::{HOSTILE, damage, mutate};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Valid inputs the mutations start from, made once.
struct Seeds {
    species: Vec<Vec<u8>>,
    parameters: Vec<String>,
    arbaro: Vec<Vec<u8>>,
    fields: Vec<Vec<u8>>,
    tree_file: Vec<u8>,
    glb: Vec<u8>,
}

impl Seeds {
    fn make(dir: &Path) -> Self {
        let files = |folder: PathBuf, ext: &str| -> Vec<Vec<u8>> {
            let mut paths: Vec<PathBuf> = std::fs::read_dir(&folder)
                .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
                .flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == ext))
                .collect();
            paths.sort();
            paths.iter().map(|p| read(p)).collect()
        };
        let species = files(repo("species"), "toml");
        // Parameter names as the species files spell them.
        let text = String::from_utf8_lossy(&species[0]).into_owned();
        let parameters = text
            .lines()
            .filter_map(|l| l.split_once('=').map(|(k, _)| k.trim().to_string()))
            .filter(|k| !k.is_empty() && !k.starts_with('#') && !k.contains(' '))
            .collect();
        let make = |args: &[&str], file: &str| {
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_sylva"))
                .args(args)
                .current_dir(dir)
                .env("SYLVA_RENDERER", "cpu")
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{args:?}: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            read(&dir.join(file))
        };
        Self {
            species,
            parameters,
            arbaro: files(repo("../shared/data/arbaro-species"), "xml"),
            fields: files(repo("species/fields"), "toml"),
            tree_file: make(&["lobes", "black_oak", "-o", "seed.tree"], "seed.tree"),
            glb: make(
                &["generate", "hazel", "--quality", "0.2", "-o", "seed.glb"],
                "seed.glb",
            ),
        }
    }
}

/// A small valid point cloud: a trunk and a round crown, as XYZ text.
fn cloud(rng: &mut Rng, n: usize) -> String {
    let mut text = String::new();
    for i in 0..n {
        let u = (rng.next() % 10_000) as f32 / 10_000.0;
        let v = (rng.next() % 10_000) as f32 / 10_000.0;
        let (x, y, z) = if i % 5 == 0 {
            (0.0, 0.0, u * 3.0)
        } else {
            let (a, b) = (u * std::f32::consts::TAU, v * std::f32::consts::PI);
            (
                2.0 * a.cos() * b.sin(),
                2.0 * a.sin() * b.sin(),
                5.0 + 2.0 * b.cos(),
            )
        };
        text.push_str(&format!("{x:.3} {y:.3} {z:.3}\n"));
    }
    text
}

fn ply(xyz: &str) -> String {
    let n = xyz.lines().count();
    format!(
        "ply\nformat ascii 1.0\nelement vertex {n}\nproperty float x\nproperty float y\n\
         property float z\nend_header\n{xyz}"
    )
}

/// The cases of one family.
fn family(name: &'static str, seeds: &Seeds, rng: &mut Rng, n: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for _ in 0..n {
        let case = match name {
            "species-toml" => {
                let source = rng.pick(&seeds.species);
                let body = mutate(rng, source);
                Case::new(name, &["generate", "tree.toml", "-o", "out.glb"]).file("tree.toml", body)
            }
            "set-values" => {
                let p = rng.pick(&seeds.parameters).clone();
                let v = *rng.pick(&HOSTILE);
                let set = format!("{p}={v}");
                Case::new(
                    name,
                    &[
                        "generate",
                        "quaking_aspen",
                        "--quality",
                        "0.3",
                        "-o",
                        "out.glb",
                    ],
                )
                .names(&[p.as_str()])
                .with_args(&["--set", &set])
            }
            "arbaro-xml" => {
                let source = rng.pick(&seeds.arbaro);
                let body = mutate(rng, source);
                Case::new(
                    name,
                    &["generate", "tree.xml", "--quality", "0.3", "-o", "out.glb"],
                )
                .file("tree.xml", body)
            }
            "fields-rules" => {
                let source = rng.pick(&seeds.fields);
                let body = mutate(rng, source);
                Case::new(name, &["lobes", "rules.toml", "-o", "out.glb"]).file("rules.toml", body)
            }
            "tree-file" => {
                let body = mutate(rng, &seeds.tree_file);
                Case::new(name, &["lobes", "in.tree", "-o", "out.glb"]).file("in.tree", body)
            }
            "point-cloud" => {
                let count = 60 + rng.below(200);
                let xyz = cloud(rng, count);
                let (file, body) = if rng.below(2) == 0 {
                    ("scan.xyz", xyz)
                } else {
                    ("scan.ply", ply(&xyz))
                };
                let body = mutate(rng, body.as_bytes());
                Case::new(
                    name,
                    &["lobes", "black_oak", "--points", file, "-o", "out.glb"],
                )
                .file(file, body)
            }
            "profiles" => {
                let (file, source) = *rng.pick(&[
                    ("p.csv", "profiles/round.csv"),
                    ("p.csv", "profiles/conifer.csv"),
                    ("p.svg", "profiles/vase.svg"),
                    ("b.csv", "profiles/sticks.csv"),
                ]);
                let body = mutate(rng, &read(&repo(source)));
                let args: &[&str] = if file == "b.csv" {
                    &["stick", "--branches", file, "-o", "out.glb"]
                } else {
                    &["whisk", "--profile", file, "-o", "out.glb"]
                };
                Case::new(name, args).file(file, body)
            }
            "fractal-flags" => {
                let flag = *rng.pick(&[
                    "--theta1",
                    "--theta2",
                    "--r1",
                    "--r2",
                    "--depth",
                    "--tip-daughters",
                    "--vary-length",
                    "--vary-angle",
                    "--seed",
                    "--trunk-length",
                    "--trunk-radius",
                    "--max-segments",
                    "--size",
                ]);
                let value = *rng.pick(&HOSTILE);
                let out = *rng.pick(&["out.vec", "out.svg", "out.png", "out.glb"]);
                let flag_value = format!("{flag}={value}");
                Case::new(name, &["fractal", "--depth", "8", "-o", out])
                    .with_args(&[&flag_value])
                    .names(&[flag.trim_start_matches('-'), flag])
            }
            "forest-toml" => {
                let seed = "[forest]\nspecies = [\"hazel\", \"quaking_aspen\"]\ncount = 6\n\
                            area = [20, 20]\nseed = 3\nvariants = 2\nquality = 0.2\n";
                let body = mutate(rng, seed.as_bytes());
                Case::new(name, &["forest", "f.toml", "-o", "out.glb"]).file("f.toml", body)
            }
            "grow-flags" => {
                let species = *rng.pick(&["PLAC", "MAGR", "CESI4", "QUAG", "XXXX", "", "plac"]);
                let region = *rng.pick(&["InlVal", "NoCalC", "Nowhere", ""]);
                let from = *rng.pick(&["0", "5", "-3", "400", "nan", "1e9"]);
                let to = *rng.pick(&["10", "64", "500", "inf", "2"]);
                let step = *rng.pick(&["1", "0", "-1", "nan", "1e9", "3"]);
                Case::new(name, &["grow", species, "--no-pictures", "-o", "out"])
                    .with_args(&[
                        "--region", region, "--from", from, "--to", to, "--step", step,
                    ])
                    .names(&[
                        species, region, "--from", "--to", "--step", "from", "to", "step",
                    ])
            }
            "street-toml" => {
                // A site, a prices or a costs file, mutated, under a short run of a plane.
                let (flag, file, body) = match rng.below(3) {
                    0 => {
                        let site = *rng.pick(&[
                            "sites/narrow-under-wires.toml",
                            "sites/boulevard.toml",
                            "sites/facade-3m.toml",
                        ]);
                        ("--site", "s.toml", read(&repo(site)))
                    }
                    1 => ("--prices", "p.toml", PRICES.as_bytes().to_vec()),
                    _ => ("--costs", "c.toml", COSTS.as_bytes().to_vec()),
                };
                let body = mutate(rng, &body);
                Case::new(
                    name,
                    &[
                        "grow",
                        "PLAC",
                        "--from",
                        "3",
                        "--to",
                        "4",
                        "--no-pictures",
                        "-o",
                        "out",
                    ],
                )
                .with_args(&[flag, file])
                .file(file, body)
            }
            "damaged-glb" => {
                let body = damage(rng, &seeds.glb);
                let mut case = Case::new(
                    name,
                    &["render", "in.glb", "--size", "64x64", "-o", "out.png"],
                )
                .file("in.glb", body);
                // Now and then through the GPU backend too, where there is one.
                if rng.below(4) == 0 {
                    case.env.clear();
                }
                case
            }
            other => panic!("no family {other}"),
        };
        cases.push(case);
    }
    cases
}

/// Output paths that cannot be written, for every command that writes.
fn output_cases() -> Vec<Case> {
    let writers: [&[&str]; 7] = [
        &["generate", "hazel", "--quality", "0.2", "-o"],
        &["fractal", "--depth", "6", "-o"],
        &["lobes", "black_oak", "-o"],
        &[
            "render",
            "hazel",
            "--quality",
            "0.2",
            "--size",
            "64x64",
            "-o",
        ],
        &[
            "forest",
            "--species",
            "hazel",
            "--count",
            "3",
            "--quality",
            "0.2",
            "-o",
        ],
        &["draw", "hazel", "-o"],
        &["whisk", "--profile", "p.csv", "-o"],
    ];
    let targets = [
        "missing/folder/out.glb",
        "missing/folder/out.png",
        "out.unknown",
        "full.glb",
        "full.png",
        "full.svg",
        "a-folder",
        "",
    ];
    let mut cases = Vec::new();
    for w in writers {
        for t in targets {
            let mut case = Case::new("output-paths", w)
                .with_args(&[t])
                .file("p.csv", b"radius,height\n0,0\n2,3\n0,6\n".to_vec());
            case.names = vec![t.to_string()];
            if t.is_empty() {
                case.names = vec!["output".into()];
            }
            cases.push(case);
        }
    }
    cases
}

impl Case {
    fn with_args(mut self, args: &[&str]) -> Self {
        self.args.extend(args.iter().map(|a| a.to_string()));
        self
    }
}

const FAMILIES: [&str; 12] = [
    "species-toml",
    "set-values",
    "arbaro-xml",
    "fields-rules",
    "tree-file",
    "point-cloud",
    "profiles",
    "fractal-flags",
    "forest-toml",
    "grow-flags",
    "street-toml",
    "damaged-glb",
];

/// Seeds for the street family (test figures, not a city's).
const PRICES: &str = "source = \"test\"\nyear = 2024\nelectricity_per_kwh = 0.3\n\
natural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\n\
ozone_per_kg = 11.0\nnox_per_kg = 28.2\npm10_per_kg = 20.7\nso2_per_kg = 8.2\nvoc_per_kg = 10.3\n";
const COSTS: &str = "source = \"test\"\nyear = 2024\nplanting = 200.0\n\
establishment_per_year = 50.0\nestablishment_years = 3\nremoval_per_cm_dbh = 20.0\n\
removal_chance_per_year = 0.01\nsidewalk_repair_per_year = 4.0\ncleanup_per_year = 3.0\n\
[[pruning]]\nup_to_dbh_cm = 15.0\nprice = 30.0\ncycle_years = 3\n";

/// What became of one case: its folder (kept only where it broke a rule), its outcome, and the
/// rule it broke.
type Ran = (PathBuf, harness::Outcome, Option<String>);

/// Runs every case, each in a fresh folder of its own, on twice as many threads as there are
/// cores; the outcomes come back in the cases' order.
fn run_all(all: &[Case], root: &Path) -> Vec<Ran> {
    let next = AtomicUsize::new(0);
    // Most cases are a process that starts, reads a little and refuses: much of their time is
    // spent starting up and writing files, not computing, and one case per core left the two
    // cores of a CI machine a quarter idle. Twice as many keep them busy; no case comes near
    // the time limit even so (the slowest, a growth, takes some 14 s of its 90).
    let threads = 2 * std::thread::available_parallelism().map_or(1, |n| n.get());
    let done: Mutex<Vec<Option<Ran>>> = Mutex::new((0..all.len()).map(|_| None).collect());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(case) = all.get(i) else { break };
                    let dir = scratch(root, case.family, i);
                    // Cases that write into special files: a link to /dev/full, a folder in
                    // the way.
                    for name in ["full.glb", "full.png", "full.svg"] {
                        if case.args.iter().any(|a| a == name) {
                            std::os::unix::fs::symlink("/dev/full", dir.join(name)).unwrap();
                        }
                    }
                    if case.args.iter().any(|a| a == "a-folder") {
                        std::fs::create_dir(dir.join("a-folder")).unwrap();
                    }
                    let outcome = run(case, &dir);
                    // A case's folder goes as soon as it is judged: a campaign writes some
                    // gigabytes of trees in all (a Fields tree of random rules can be 150 MB),
                    // more than a CI machine's disk holds at once. Broken cases keep theirs.
                    let why = broken(case, &outcome);
                    if why.is_none() {
                        let _ = std::fs::remove_dir_all(&dir);
                    }
                    done.lock().unwrap()[i] = Some((dir, outcome, why));
                }
            });
        }
    });
    done.into_inner()
        .unwrap()
        .into_iter()
        .map(|o| o.expect("every case ran"))
        .collect()
}

#[test]
fn no_input_makes_sylva_panic_hang_or_leave_a_partial_file() {
    let n = env_number("SYLVA_FUZZ_CASES", 8) as usize;
    let seed = env_number("SYLVA_FUZZ_SEED", 1);
    let root = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("fuzz");
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root).unwrap();
    let seeds = Seeds::make(&root);
    let mut all: Vec<Case> = Vec::new();
    for (k, f) in FAMILIES.iter().enumerate() {
        let mut rng = Rng::new(seed.wrapping_mul(1000).wrapping_add(k as u64));
        all.extend(family(f, &seeds, &mut rng, n));
    }
    all.extend(output_cases());
    // Most cases are a short refusal on one thread: several run side by side, each in its own
    // folder, and their outcomes are tallied in case order below.
    let outcomes = run_all(&all, &root);
    let mut failures = Vec::new();
    let mut table: Vec<(&str, [usize; 3], f64, i64)> = Vec::new();
    for (case, (dir, outcome, why)) in all.iter().zip(outcomes) {
        let row = match table.iter_mut().find(|r| r.0 == case.family) {
            Some(r) => r,
            None => {
                table.push((case.family, [0; 3], 0.0, 0));
                table.last_mut().unwrap()
            }
        };
        row.2 = row.2.max(outcome.seconds);
        row.3 = row.3.max(outcome.peak_kb);
        match why {
            None if outcome.code == Some(0) => row.1[0] += 1,
            None => row.1[1] += 1,
            Some(why) => {
                row.1[2] += 1;
                failures.push(format!(
                    "[{}] sylva {} ({why}; exit {:?})\n  files: {:?}\n  stderr: {}\n  case folder: {}",
                    case.family,
                    case.args.join(" "),
                    outcome.code,
                    case.files.iter().map(|f| &f.0).collect::<Vec<_>>(),
                    outcome.stderr.trim(),
                    dir.display()
                ));
            }
        }
    }
    eprintln!("fuzz campaign, seed {seed}, {n} cases per family:");
    eprintln!(
        "  {:<14} {:>8} {:>8} {:>8} {:>10} {:>10}",
        "family", "accepted", "refused", "broken", "slowest s", "peak MB"
    );
    for (f, [ok, refused, bad], slowest, peak) in &table {
        eprintln!(
            "  {f:<14} {ok:>8} {refused:>8} {bad:>8} {slowest:>10.2} {:>10}",
            peak >> 10
        );
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases broke the rules:\n{}",
        failures.len(),
        all.len(),
        failures.join("\n")
    );
}
