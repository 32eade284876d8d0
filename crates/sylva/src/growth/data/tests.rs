//! The sources' data read and evaluated: each equation form on known inputs, the spec's check
//! values, palms' fitted ages, species lookup, broken tables and DBH classes.

use crate::growth::*;

fn close(got: f64, want: f64, tolerance: f64) -> bool {
    (got - want).abs() <= tolerance * want.abs().max(1e-9)
}
#[test]
fn london_plane_matches_the_spec_check_values() {
    let m = Database::builtin().find("InlVal", "PLAC").unwrap();
    // age: DBH cm, H m, CD m, CH m, LA m2 (spec section 1, rounded there).
    let want = [
        (10.0, [25.7, 11.0, 8.7, 8.6, 177.0]),
        (20.0, [40.6, 15.0, 12.5, 11.2, 300.0]),
        (30.0, [49.2, 16.7, 14.3, 12.4, 369.0]),
        (40.0, [53.3, 17.4, 15.0, 12.9, 401.0]),
        (50.0, [54.7, 17.6, 15.3, 13.1, 412.0]),
    ];
    for (t, w) in want {
        let got = [
            m.dbh(t),
            m.height(t),
            m.crown_diameter(t),
            m.crown_height_fitted(t),
            m.leaf_area(t),
        ];
        for (g, w) in got.iter().zip(w) {
            // Rounded to 3 significant figures in the spec.
            assert!(close(*g, w, 0.006), "age {t}: {got:?} vs {w:?}");
        }
    }
}

#[test]
fn silver_maple_matches_the_spec_check_value() {
    let m = Database::builtin().find("InlVal", "silver maple").unwrap();
    let got = [
        m.dbh(30.0),
        m.height(30.0),
        m.crown_diameter(30.0),
        m.crown_height_fitted(30.0),
        m.leaf_area(30.0),
    ];
    for (g, w) in got.iter().zip([52.0, 17.5, 12.9, 14.6, 437.0]) {
        assert!(close(*g, w, 0.006), "{got:?}");
    }
}

fn eq(form: Form, c: [f64; 5], mse: f64) -> Equation {
    Equation {
        form,
        coefficients: c,
        mse,
        range: (0.0, 1e9),
    }
}

#[test]
fn every_form_on_known_inputs() {
    let c = [0.5, 1.5, 0.25, -0.01, 0.001];
    let x: f64 = 4.0;
    let ll = (x + 1.0).ln().ln();
    let mse = 0.2;
    let cases = [
        (Form::Lin, 0.5 + 1.5 * 4.0),
        (Form::Quad, 0.5 + 6.0 + 0.25 * 16.0),
        (Form::Cub, 0.5 + 6.0 + 4.0 - 0.64),
        (Form::Quart, 0.5 + 6.0 + 4.0 - 0.64 + 0.256),
        (
            Form::LogLogW1,
            (0.5 + 1.5 * ((5.0f64).ln() + 0.1).ln()).exp(),
        ),
        (Form::LogLogW2, (0.5 + 1.5 * ll + 2.0 * 0.1).exp()),
        (Form::LogLogW3, (0.5 + 1.5 * ll + 4.0 * 0.1).exp()),
        (Form::LogLogW4, (0.5 + 1.5 * ll + 16.0 * 0.1).exp()),
        (Form::ExPow1, (0.5 + 6.0 + 0.1f64).exp()),
        (Form::ExPow2, (0.5 + 6.0 + 2.0 * 0.1f64).exp()),
        (Form::ExPow3, (0.5 + 6.0 + 4.0 * 0.1f64).exp()),
        (Form::ExPow4, (0.5 + 6.0 + 16.0 * 0.1f64).exp()),
    ];
    for (form, want) in cases {
        let got = eq(form, c, mse).raw(x);
        assert!(close(got, want, 1e-12), "{form}: {got} vs {want}");
        assert_eq!(Form::from_name(&form.name().to_uppercase()), Some(form));
    }
    // Log-log forms are undefined at 0 (the reason growth starts at age 1 for them).
    // With b > 0 that is exp(-inf) = 0 rather than a value.
    assert_eq!(eq(Form::LogLogW2, c, mse).raw(0.0), 0.0);
    // Every form of the built-in database is one of the twelve and evaluates finitely in range.
    let db = Database::builtin();
    let published = db.rows().iter().filter(|r| r.fitted_to.is_none()).count();
    assert_eq!(published, 2402);
    let mut seen = std::collections::HashSet::new();
    for r in db.rows() {
        seen.insert(r.equation.form);
    }
    assert_eq!(seen.len(), 12, "all twelve forms occur in TS6");
}

#[test]
fn quadratics_that_turn_over_are_held_at_their_vertex() {
    let e = eq(Form::Quad, [1.0, 2.0, -0.1, 0.0, 0.0], 0.0);
    // Vertex at x = 10.
    assert!((e.rise_end(0.0, 50.0) - 10.0).abs() < 1e-6);
    assert_eq!(e.rise_end(0.0, 5.0), 5.0);
}

#[test]
fn column_d_replaces_c_as_the_bias_term_where_it_is_filled() {
    let db = Database::builtin();
    let row = db
        .rows()
        .iter()
        .find(|r| {
            r.region == "SacVal"
                && r.code == "CEDE"
                && r.input == Quantity::Dbh
                && r.output == Quantity::Age
        })
        .unwrap();
    assert_eq!(row.equation.form, Form::LogLogW1);
    assert_eq!(row.equation.mse, 0.09235);
}

#[test]
fn crown_base_never_sinks_and_ages_stay_in_range() {
    let db = Database::builtin();
    let mut checked = 0;
    for region in db.regions() {
        for s in db.growable(&region.code) {
            let m = db.find(&region.code, &s.code).unwrap();
            assert!(
                m.ages.1 > m.ages.0,
                "{} {}: {:?}",
                region.code,
                s.code,
                m.ages
            );
            let mut last = 0.0;
            let mut t = m.ages.0;
            while t <= m.ages.1 {
                let base = m.crown_base(t);
                assert!(base + 1e-9 >= last, "{} {} at {t}", region.code, s.code);
                assert!(m.crown_height(t) <= m.height(t) + 1e-9);
                for v in [m.dbh(t), m.height(t), m.crown_diameter(t), m.leaf_area(t)] {
                    assert!(
                        v.is_finite() && v > 0.0,
                        "{} {} at {t}",
                        region.code,
                        s.code
                    );
                }
                last = base;
                t += 0.5;
            }
            checked += 1;
        }
    }
    assert!(checked > 300, "{checked} species grown");
}

#[test]
fn species_are_found_by_code_scientific_or_common_name_and_errors_say_what_exists() {
    let db = Database::builtin();
    for q in [
        "PLAC",
        "plac",
        "Platanus x acerifolia",
        "london_planetree",
        "London Planetree",
    ] {
        assert_eq!(db.find("InlVal", q).unwrap().species.code, "PLAC", "{q}");
    }
    assert_eq!(db.find("CenFla", "ACRU").unwrap().region.city, "Orlando");
    let e = db.find("Atlantis", "PLAC").unwrap_err().to_string();
    assert!(e.contains("Atlantis") && e.contains("InlVal"), "{e}");
    let e = db.find("InlVal", "plane").unwrap_err().to_string();
    assert!(e.contains("`plane`") && e.contains("PLAC"), "{e}");
    // Modesto's fan palm has DBH equations but no measured palms to fit its age -> DBH to;
    // Orlando's has both.
    let e = db.find("InlVal", "WARO").unwrap_err().to_string();
    assert!(e.contains("age -> DBH"), "{e}");
    assert!(db.find("CenFla", "WARO").is_ok());
    // Suggestions are species that can be grown: not the palm.
    let e = db.find("InlVal", "nothing").unwrap_err().to_string();
    assert!(e.contains("PLAC") && !e.contains("WARO"), "{e}");
}

/// Every palm whose measured trees thicken with age gets a rising fit inside them;
/// species with a published age→DBH get none.
#[test]
fn every_palm_gets_a_rising_age_to_dbh_within_its_trees() {
    let db = Database::builtin();
    let fitted: Vec<&crate::growth::data::database::Row> =
        db.rows().iter().filter(|r| r.fitted_to.is_some()).collect();
    // 13 palm species and regions have measured ages; in one, the desert fan palm of the
    // Southwest desert (71 trees), DBH does not rise with age at all.
    assert_eq!(fitted.len(), 12, "one fit per palm species and region");
    assert!(!fitted.iter().any(|r| r.code == "WAFI"));
    for r in &fitted {
        assert!(r.code.len() >= 4, "{r:?}");
        let (lo, hi) = r.equation.range;
        assert!(
            lo > 1.0 && hi > lo && hi < 150.0,
            "{} {}: {lo} {hi}",
            r.region,
            r.code
        );
        assert!(r.equation.raw(20.0) > r.equation.raw(5.0), "{r:?}");
    }
    // Nothing else is fitted: the plane keeps its published equation.
    assert!(fitted.iter().all(|r| r.code != "PLAC"));
}

#[test]
fn a_broken_table_names_its_file_and_line() {
    let ts6 = "Region,Scientific Name,SpCode,Independent variable,Predicts component ,Units,Model weight,EqName,a,b,c,d,e,Apps min,Apps max\n\
               InlVal,X y,XY,age,dbh,cm,1,lin,1,2,,,,1,50\n\
               InlVal,X y,XY,age,dbh,cm,1,wiggle,1,2,,,,1,50\n";
    let e = Database::parse(ts6, "", "", "mydb")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("mydb/TS6") && e.contains("line 3") && e.contains("wiggle"),
        "{e}"
    );
    let ts6 = ts6.replace("wiggle,1,2", "lin,one,2");
    let e = Database::parse(&ts6, "", "", "mydb")
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 3") && e.contains("`one`"), "{e}");
}

#[test]
fn the_age_of_a_dbh_inverts_the_age_to_dbh_equation_within_its_ages() {
    let m = Database::builtin().find("InlVal", "PLAC").unwrap();
    for t in [m.ages.0 + 0.5, 10.0, 25.0, m.ages.1 - 0.5] {
        let back = m.age_at_dbh(m.dbh(t));
        assert!((back - t).abs() < 1e-6, "{t} -> {} cm -> {back}", m.dbh(t));
    }
    assert_eq!(m.age_at_dbh(0.01), m.ages.0);
    assert_eq!(m.age_at_dbh(f64::NAN), m.ages.0);
    assert_eq!(m.age_at_dbh(10_000.0), m.ages.1);
}

#[test]
fn trees_are_counted_by_dbh_class_as_table_ts2_counts_them() {
    let db = Database::builtin();
    let plane = db
        .species()
        .iter()
        .find(|s| s.region == "InlVal" && s.code == "PLAC")
        .expect("listed");
    assert_eq!(plane.trees_by_dbh_class, [2, 0, 10, 7, 5, 3, 0, 0, 0]);
    // TS2's grand totals add up to the 14,487 trees of the survey.
    let all: u32 = db
        .species()
        .iter()
        .map(|s| s.trees_by_dbh_class.iter().sum::<u32>())
        .sum();
    assert_eq!(all, 14_487);
    let ts2 = "Region,Scientific Name,Common Name,SpCode,Tree Type,Dbh_class1\nInlVal,X y,x,XY,BDL,many\n";
    let ts6 = "Region,Scientific Name,SpCode,Independent variable,Predicts component ,Units,Model weight,EqName,a,b,c,d,e,Apps min,Apps max\n\
               InlVal,X y,XY,age,dbh,cm,1,lin,1,2,,,,1,50\n";
    let e = Database::parse(ts6, ts2, "", "mydb")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("mydb/TS2") && e.contains("line 2") && e.contains("`many`"),
        "{e}"
    );
}
