//! Grown trees held to their data: every measured dimension within the bounds at
//! every whole age, the form each habit asks, determinism, and the grower's own measures.

use super::*;
use data::habit;
use glam::Vec3;
use survey::form;

fn close(got: f64, want: f64, tolerance: f64) -> bool {
    (got - want).abs() <= tolerance * want.abs().max(1e-9)
}

/// What one fidelity run found.
pub(crate) struct Fidelity {
    /// Worst relative error per quantity (height, DBH, crown diameter, crown height, leaf
    /// area) over every whole age in the fitted range...
    pub worst: [f64; 5],
    /// ...and the age of each.
    pub at: [u32; 5],
    /// The form at ages 30, 35 and 40, where the range holds them.
    pub forms: Vec<(u32, form::FormMeasures)>,
}

/// Grows a species through its fitted range (to `last` at most), measuring it at every whole
/// age.
pub(crate) fn fidelity(region: &str, code: &str, seed: u64, last: u32) -> Fidelity {
    let m = Database::builtin().find(region, code).unwrap();
    let ages = m.whole_ages().filter(|&a| a <= last);
    let mut g = Grower::new(
        m,
        GrowthOptions {
            seed,
            ..Default::default()
        },
    );
    let mut worst = [0.0f64; 5];
    let mut at = [0u32; 5];
    let mut forms = Vec::new();
    for age in ages {
        g.advance_to(age as f64);
        let skeleton = g.skeleton();
        let d = measure(&skeleton);
        let t = g.targets(age as f64);
        let errs = d.relative_errors(&t);
        for k in 0..5 {
            if errs[k].abs() > worst[k].abs() {
                worst[k] = errs[k];
                at[k] = age;
            }
        }
        if [30, 35, 40].contains(&age) {
            let base = d.height - d.crown_height;
            let form = form::measure_form(&skeleton, base, d.height, d.crown_diameter);
            forms.push((age, form));
        }
    }
    Fidelity { worst, at, forms }
}

fn habit_in(region: &str, code: &str) -> habit::Habit {
    let m = Database::builtin().find(region, code).unwrap();
    habit::habit_of(code, &m.species.tree_type)
}

/// The form the issue asks of a grown tree at 30 to 40 years: a palm has no leader; a decurrent broadleaf (apical
/// control under 0.5) has at least a quarter of its leaf area within half the crown radius,
/// two or more leaders and scaffolds 30-60 degrees above the horizontal; a conifer keeps its
/// one leader; an oval broadleaf keeps its leader, though a lateral may rise beside it as a
/// second (as in old magnolias and sweetgums). Every form has the pipe model's exponent.
fn form_problems(code: &str, run: &Fidelity, habit: &habit::Habit) -> Vec<String> {
    if habit.form == habit::TreeForm::Palm {
        // Nothing woody in a palm's crown: no leader, no fork.
        return run
            .forms
            .iter()
            .filter(|(_, f)| f.leaders != 0 || f.pipe_exponent.is_some())
            .map(|(age, f)| format!("{code} at {age}: a palm with {f:?}"))
            .collect();
    }
    let decurrent = habit.apical_control < 0.5;
    let leaders = if habit.form == habit::TreeForm::ExcurrentConifer {
        1..=1
    } else {
        1..=2
    };
    let mut problems = Vec::new();
    for (age, f) in &run.forms {
        let mut check = |ok: bool, what: String| {
            if !ok {
                problems.push(format!("{code} at {age}: {what}"));
            }
        };
        let angle = f.scaffold_angle.unwrap_or(f64::NAN);
        let exponent = f.pipe_exponent.unwrap_or(f64::NAN);
        check(
            (exponent - model::PIPE_EXPONENT as f64).abs() < 0.2,
            format!("pipe exponent {exponent:.2}"),
        );
        if decurrent {
            check(
                f.inner_leaf_share >= 0.25,
                format!("inner leaf share {:.3}", f.inner_leaf_share),
            );
            // Two or more leaders: held over four seeds in `assert_faithful`.
            check(
                (30.0..=60.0).contains(&angle),
                format!("scaffold angle {angle:.1}"),
            );
        } else {
            check(
                leaders.contains(&f.leaders),
                format!("{} leaders", f.leaders),
            );
        }
    }
    problems
}

/// The bounds: height and DBH within 5% of the measured functions, crown diameter,
/// crown height and leaf area within 10%, at every whole age of the fitted range, and the form
/// of `form_problems`.
///
/// The growth is chaotic (a rounding can shed a different twig), so the bounds are held at
/// two seeds: at seed 1 over the whole fitted range, at seed 2 through age 40.
///
/// A decurrent crown's leaders are counted over four seeds (1-4, at 30, 35 and 40 years), and
/// two crowns in the twelve may have a single leader. Whether the crown is divided turns on a
/// second limb's radius against 2/3 of the thickest ([`form`]'s codominance line), and a limb
/// near that line crosses it from one seed to the next (PICH at seed 2 and 40 years with issue
/// BB's step schedule: its thickest limb 6.6 cm across the plane, the next 4.3 cm). Over the
/// eight decurrent species of these tests, seeds 0-5, one crown in 36 has a single leader (4 of 144),
/// with 20 steps a year and with the schedule alike; at that rate three in twelve come once in
/// a few hundred species, and a crown that lost its division would fail at once.
fn assert_faithful(region: &str, code: &str) {
    let habit = habit_in(region, code);
    let decurrent = habit.form != habit::TreeForm::Palm && habit.apical_control < 0.5;
    let mut broken = Vec::new();
    let mut crowns = Vec::new();
    for (seed, last) in [(1, u32::MAX), (2, 40), (3, 40), (4, 40)] {
        // Seeds 3 and 4 only count a decurrent crown's leaders.
        if seed > 2 && !decurrent {
            break;
        }
        let run = fidelity(region, code, seed, last);
        crowns.extend(run.forms.iter().map(|(age, f)| (seed, *age, f.leaders)));
        if seed > 2 {
            continue;
        }
        let mut problems = run_problems(&run);
        problems.extend(form_problems(code, &run, &habit));
        broken.extend(problems.into_iter().map(|p| format!("seed {seed}: {p}")));
    }
    let single: Vec<_> = crowns.iter().filter(|c| c.2 < 2).collect();
    if decurrent && single.len() > 2 {
        broken.push(format!(
            "single-leader crowns (seed, age, leaders): {single:?}"
        ));
    }
    assert!(broken.is_empty(), "{region} {code}: {}", broken.join(", "));
}

/// The measured dimensions outside the bounds.
fn run_problems(run: &Fidelity) -> Vec<String> {
    let names = [
        "height",
        "DBH",
        "crown diameter",
        "crown height",
        "leaf area",
    ];
    let bounds = [0.05, 0.05, 0.10, 0.10, 0.10];
    (0..5)
        .filter(|&k| run.worst[k].abs() > bounds[k])
        .map(|k| {
            let (worst, at) = (run.worst[k], run.at[k]);
            format!("{} {:+.1}% at age {at}", names[k], worst * 100.0)
        })
        .collect()
}

#[test]
fn faithful_london_plane() {
    assert_faithful("InlVal", "PLAC");
}

#[test]
fn faithful_silver_maple() {
    assert_faithful("InlVal", "ACSA1");
}

#[test]
fn faithful_modesto_ash() {
    assert_faithful("InlVal", "FRVE_G");
}

#[test]
fn faithful_goldenrain_tree() {
    assert_faithful("InlVal", "KOPA");
}

#[test]
fn faithful_southern_magnolia() {
    assert_faithful("InlVal", "MAGR");
}

#[test]
fn faithful_chinese_pistache() {
    assert_faithful("InlVal", "PICH");
}

#[test]
fn faithful_chinese_hackberry() {
    assert_faithful("InlVal", "CESI4");
}

// Beyond Modesto: a cherry and a red oak of the Pacific Northwest, the coast redwood of the
// northern California coast (a conifer, which keeps one leader), and Orlando's Mexican fan
// palm (its age -> DBH fitted to the measured palms). One test each, so that the test
// threads share them.
#[test]
fn faithful_pacific_northwest_cherry() {
    assert_faithful("PacfNW", "PRSE2");
}

#[test]
fn faithful_pacific_northwest_red_oak() {
    assert_faithful("PacfNW", "QURU");
}

#[test]
fn faithful_coast_redwood() {
    assert_faithful("NoCalC", "SESE");
}

#[test]
fn faithful_mexican_fan_palm() {
    assert_faithful("CenFla", "WARO");
}

/// The crown the grower steers by is the crown `measure` finds on its skeleton.
#[test]
fn the_grower_measures_its_crown_as_the_survey_does() {
    let m = Database::builtin().find("InlVal", "KOPA").unwrap();
    let mut g = Grower::new(m, GrowthOptions::default());
    for age in [2.0, 5.5, 9.0] {
        g.advance_to(age);
        let (diameter, height) = g.crown_now();
        let d = measure(&g.skeleton());
        assert!(
            (diameter - d.crown_diameter).abs() < 1e-3,
            "{diameter} {d:?}"
        );
        assert!((height - d.crown_height).abs() < 1e-3, "{height} {d:?}");
    }
}

/// Prints the worst errors; SEED, REGION and CODES (comma-separated, or `all`) choose what.
#[test]
#[ignore]
fn print_fidelity() {
    let seed: u64 = std::env::var("SEED").map_or(1, |s| s.parse().unwrap());
    let region = std::env::var("REGION").unwrap_or("InlVal".into());
    let codes = std::env::var("CODES").unwrap_or("PLAC,ACSA1,FRVE_G,KOPA,MAGR,PICH,CESI4".into());
    // `CODES=all`: every species of the region that can be grown.
    let codes: Vec<String> = if codes == "all" {
        let db = Database::builtin();
        db.growable(&region)
            .iter()
            .map(|s| s.code.clone())
            .collect()
    } else {
        codes.split(',').map(str::to_string).collect()
    };
    for code in &codes {
        let code = code.as_str();
        let t = std::time::Instant::now();
        let run = fidelity(&region, code, seed, u32::MAX);
        let mut problems = run_problems(&run);
        problems.extend(form_problems(code, &run, &habit_in(&region, code)));
        let (w, at) = (run.worst, run.at);
        println!(
            "{code:7} H {:+.3}@{} DBH {:+.3}@{} CD {:+.3}@{} CH {:+.3}@{} LA {:+.3}@{}  {:.1}s",
            w[0],
            at[0],
            w[1],
            at[1],
            w[2],
            at[2],
            w[3],
            at[3],
            w[4],
            at[4],
            t.elapsed().as_secs_f64()
        );
        for (age, f) in &run.forms {
            println!(
                "  {age}: inner {:.3} leaders {} scaffolds {:.1}",
                f.inner_leaf_share,
                f.leaders,
                f.scaffold_angle.unwrap_or(f64::NAN)
            );
        }
        for p in problems {
            println!("  {p}");
        }
    }
}

#[test]
#[ignore]
fn print_ages() {
    let code = std::env::var("SP").unwrap_or("PLAC".into());
    let region = std::env::var("REGION").unwrap_or("InlVal".into());
    let m = Database::builtin().find(&region, &code).unwrap();
    let fine: f64 = std::env::var("FINE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1.0);
    let last: f64 = std::env::var("LAST")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1e9);
    let ages: Vec<f64> = m
        .whole_ages()
        .flat_map(|a| (0..(1.0 / fine).round() as usize).map(move |k| a as f64 + k as f64 * fine))
        .filter(|&a| a <= last)
        .collect();
    let mut g = Grower::new(
        m,
        GrowthOptions {
            seed: std::env::var("SEED").map_or(1, |s| s.parse().unwrap()),
            ..Default::default()
        },
    );
    for age in ages {
        let t0 = std::time::Instant::now();
        g.advance_to(age);
        let dt = t0.elapsed().as_secs_f64();
        let sk = g.skeleton();
        let d = measure(&sk);
        let t = g.targets(age);
        println!(
            "{age:5.2} H {:5.2}/{:5.2} DBH {:5.1}/{:5.1} CD {:5.2}/{:5.2} CH {:5.2}/{:5.2} LA {:6.1}/{:6.1} segs {} leaves {} {:.0}ms (growth {:.1} light {:.1} ms/step) vigour {:.2}",
            d.height,
            t.height,
            d.dbh,
            t.dbh,
            d.crown_diameter,
            t.crown_diameter,
            d.crown_height,
            t.crown_height,
            d.leaf_area,
            t.leaf_area,
            g.segment_count(),
            sk.leaves.len(),
            dt * 1e3,
            g.times.growth * 1e3,
            g.times.light * 1e3,
            g.vigour()
        );
    }
}

#[test]
fn growth_is_deterministic_and_incremental() {
    let m = Database::builtin().find("InlVal", "PLAC").unwrap();
    let options = GrowthOptions {
        seed: 3,
        ..Default::default()
    };
    let mut a = Grower::new(m.clone(), options.clone());
    a.advance_to(4.0);
    let young = a.skeleton();
    a.advance_to(7.0);
    let mut b = Grower::new(m.clone(), options.clone());
    b.advance_to(7.0);
    assert_eq!(
        a.skeleton(),
        b.skeleton(),
        "4 then 7 years equals 7 at once"
    );
    assert_ne!(young, a.skeleton());
    // Asking for a younger age does not regrow or shrink the tree.
    let before = a.skeleton();
    a.advance_to(5.0);
    assert_eq!(a.skeleton(), before);
    let mut c = Grower::new(m, GrowthOptions { seed: 4, ..options });
    c.advance_to(7.0);
    assert_ne!(c.skeleton(), b.skeleton(), "another seed, another tree");
}

#[test]
fn a_young_plane_tree_has_the_measured_height_and_dbh_and_light_thins_its_interior() {
    let m = Database::builtin().find("InlVal", "PLAC").unwrap();
    let mut g = Grower::new(
        m,
        GrowthOptions {
            seed: 1,
            ..Default::default()
        },
    );
    g.advance_to(8.0);
    let sk = g.skeleton();
    let d = measure(&sk);
    let t = g.targets(8.0);
    assert!((d.height / t.height - 1.0).abs() < 0.05, "{d:?} vs {t:?}");
    assert!((d.dbh / t.dbh - 1.0).abs() < 0.05, "{d:?} vs {t:?}");
    assert!(
        (d.leaf_area / t.leaf_area - 1.0).abs() < 0.1,
        "{d:?} vs {t:?}"
    );
    // Stems: a trunk and side branches of several orders, each starting on its parent.
    assert_eq!(sk.stems[0].level, 0);
    assert!(sk.stems.iter().any(|s| s.level >= 2));
    // The crown's interior is darker than its top.
    let light = g.light();
    let centre = Vec3::new(0.0, 0.0, (t.crown_base() + t.crown_height * 0.4) as f32);
    let top = Vec3::new(0.0, 0.0, t.height as f32 - 0.1);
    assert!(light.light_at(centre) < light.light_at(top));
}

/// Prints where a grown tree's leaves lie (radial share by tenths of the crown radius, and by
/// thirds of the crown height) and the leader count at several heights; SP, SEED and AGE.
#[test]
#[ignore]
fn print_form_detail() {
    let code = std::env::var("SP").unwrap_or("PICH".into());
    let seed: u64 = std::env::var("SEED").map_or(1, |s| s.parse().unwrap());
    let age: f64 = std::env::var("AGE").map_or(40.0, |s| s.parse().unwrap());
    let region = std::env::var("REGION").unwrap_or("InlVal".into());
    let m = Database::builtin().find(&region, &code).unwrap();
    let mut g = Grower::new(
        m,
        GrowthOptions {
            seed,
            ..Default::default()
        },
    );
    g.advance_to(age);
    let sk = g.skeleton();
    let d = measure(&sk);
    let base = d.height - d.crown_height;
    let r = d.crown_diameter as f32 / 2.0;
    let mut radial = [0.0f64; 11];
    let mut inner_by_height = [[0.0f64; 2]; 3];
    let mut total = 0.0;
    for l in &sk.leaves {
        let a = (l.length * l.width) as f64;
        let c = l.position + l.orientation * glam::Vec3::new(0.0, 0.0, l.length / 2.0);
        let k = ((c.truncate().length() / r * 10.0) as usize).min(10);
        radial[k] += a;
        let h = (((c.z as f64 - base) / d.crown_height * 3.0).max(0.0) as usize).min(2);
        inner_by_height[h][(k >= 5) as usize] += a;
        total += a;
    }
    let f = form::measure_form(&sk, base, d.height, d.crown_diameter);
    println!("{code} seed {seed} age {age}: {f:?}");
    println!(
        "radial tenths: {:?}",
        radial.map(|x| (x / total * 1000.0).round() / 1000.0)
    );
    for (h, [i, o]) in inner_by_height.iter().enumerate() {
        println!(
            "height third {h}: inner {:.3} outer {:.3}",
            i / total,
            o / total
        );
    }
    let (live, shed) = g.branch_counts();
    println!("segments {} live {live} shed {shed}", g.segment_count());
}

/// A tree too short to have a breast-height diameter (the Brazilian pepper of southern
/// California is 1.37 m tall at age 0) is measured at caliper height, as the grower holds it.
#[test]
fn a_tree_below_breast_height_is_measured_at_caliper_height() {
    use super::model::{BREAST_HEIGHT, CALIPER_HEIGHT, diameter_height};
    assert_eq!(diameter_height(1.2), CALIPER_HEIGHT);
    assert_eq!(diameter_height(3.0), BREAST_HEIGHT);
    let m = Database::builtin().find("SoCalC", "SCTE").unwrap();
    let first = m.ages.0;
    let mut g = Grower::new(m, GrowthOptions::default());
    for age in [first, first + 1.0] {
        g.advance_to(age);
        let d = measure(&g.skeleton());
        let t = g.targets(age);
        assert!(close(d.dbh, t.dbh, 0.05), "age {age}: {d:?} against {t:?}");
    }
}

/// Asked for an age past the data, the grower stops at the data's last age instead of
/// stepping for ever.
#[test]
fn growing_past_the_data_stops_at_its_last_age() {
    let m = Database::builtin().find("CenFla", "WARO").unwrap();
    let last = m.ages.1;
    let mut g = Grower::new(m, GrowthOptions::default());
    g.advance_to(f64::INFINITY);
    assert!((g.age() - last).abs() < 0.1, "{} against {last}", g.age());
    g.advance_to(f64::NAN);
    assert!((g.age() - last).abs() < 0.1);
}

/// The published crowns: most twigs 1-4 cm, numbers falling steeply through 6-10 cm ("Tree
/// branches as populations of twigs"). Before short twigs the grown plane's median twig was
/// 1.6-2.8 m and under 1% were shorter than 4 cm.
#[test]
fn a_grown_crowns_twigs_are_mostly_short() {
    let plane = Database::builtin().find("InlVal", "PLAC").unwrap();
    let mut g = Grower::new(plane, GrowthOptions::default());
    g.advance_to(g.age() + 12.0);
    let b = survey::twigs::measure_branching(&g.skeleton());
    assert!(b.share_under(4.0) > 0.4, "{b:?}");
    assert!(b.median_twig_cm.unwrap() < 6.0, "{b:?}");
    assert!(b.share_from(10.0) < 0.15, "{b:?}");
}
