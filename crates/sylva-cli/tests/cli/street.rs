//! `sylva grow --site/--prices/--costs`, `sylva rank` and `sylva wires`: what a street tree
//! gives, costs and runs into.

use crate::*;

fn repo(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(path)
}

/// Test figures only (not a city's): every key a costs file must have.
const COSTS: &str = "source = \"test figures\"\nyear = 2024\nplanting = 200.0\n\
establishment_per_year = 50.0\nestablishment_years = 3\nremoval_per_cm_dbh = 20.0\n\
removal_chance_per_year = 0.01\nsidewalk_repair_per_year = 4.0\ncleanup_per_year = 3.0\n\
[[pruning]]\nup_to_dbh_cm = 15.0\nprice = 30.0\ncycle_years = 3\n[[pruning]]\n\
up_to_dbh_cm = 200.0\nprice = 300.0\ncycle_years = 5\n";

fn column<'a>(header: &csv::StringRecord, row: &'a csv::StringRecord, name: &str) -> &'a str {
    let i = header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    &row[i]
}

#[test]
fn a_plane_under_wires_reports_benefits_costs_and_conflicts_year_by_year() {
    let dir = tempfile::tempdir().unwrap();
    let costs = dir.path().join("costs.toml");
    std::fs::write(&costs, COSTS).unwrap();
    let out = dir.path().join("out");
    let site = repo("sites/narrow-under-wires.toml");
    let run = sylva(&[
        "grow",
        "PLAC",
        "--from",
        "1",
        "--to",
        "8",
        "--site",
        site.to_str().unwrap(),
        "--costs",
        costs.to_str().unwrap(),
        "--size",
        "300x300",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let said = text(&run.stdout);
    assert!(said.contains("first conflicts: at"), "{said}");
    // Aesthetics are priced from the region's median home value (McPherson 2007's method);
    // what the cost table lacks is said.
    assert!(!said.contains("not counted: aesthetics"), "{said}");
    assert!(
        said.contains("not counted: costs of pest management"),
        "{said}"
    );
    assert!(
        said.contains("typical position from i-Tree Streets InlVal `PLAC`"),
        "{said}"
    );
    let mut reader = csv::Reader::from_path(out.join("PLAC.csv")).unwrap();
    let header = reader.headers().unwrap().clone();
    let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), 8);
    let number = |row: &csv::StringRecord, name: &str| -> f64 {
        column(&header, row, name)
            .parse()
            .unwrap_or_else(|_| panic!("{name}: {row:?}"))
    };
    // By its last age the plane's bare winter crown stands in the façade's sun.
    let last = rows.last().unwrap();
    assert!(number(last, "heating_penalty_kbtu") > 0.0, "{last:?}");
    let mut stored = 0.0;
    for row in &rows {
        let now = number(row, "co2_stored_kg");
        assert!(now > stored, "CO2 stored rises: {row:?}");
        stored = now;
        assert!(number(row, "co2_sequestered_kg") > 0.0);
        assert!(number(row, "interception_m3") > 0.0);
        assert!(number(row, "cooling_kwh") >= 0.0);
        // A deciduous plane's bare winter wood keeps some winter sun off the façade: a
        // penalty, never a gain.
        assert!(number(row, "heating_penalty_kbtu") >= 0.0, "{row:?}");
        let costs: f64 = (sylva::street::accounts::items::COSTS.iter())
            .map(|c| number(row, &format!("cost_{}_usd", c.key)))
            .sum();
        // Every category of the site's account is priced, aesthetics too.
        assert!(number(row, "value_aesthetics_usd") >= 0.0);
        let categories = [
            "aesthetics",
            "carbon",
            "co2_avoided",
            "stormwater",
            "cooling",
            "heating",
            "air_quality",
            "bvoc",
        ];
        let sum = |prefix: &str| -> f64 {
            categories
                .iter()
                .map(|b| number(row, &format!("{prefix}value_{b}_usd")))
                .sum()
        };
        assert!(
            (number(row, "net_usd") - (sum("") - costs)).abs() < 0.05,
            "{row:?}"
        );
        assert!(
            (number(row, "typical_net_usd") - (sum("typical_") - costs)).abs() < 0.05,
            "{row:?}"
        );
        // The plane emits isoprene: a cost in both accounts.
        assert!(number(row, "value_bvoc_usd") < 0.0 && number(row, "typical_value_bvoc_usd") < 0.0);
        assert!(number(row, "value_air_quality_usd") > 0.0);
    }
    // Itemised costs replace the built-in average.
    assert_eq!(number(&rows[0], "cost_average_usd"), 0.0);
    // Planting and establishment are charged while the tree establishes, then stop.
    assert_eq!(number(&rows[0], "cost_planting_usd"), 250.0);
    assert_eq!(number(&rows[7], "cost_planting_usd"), 0.0);
    // Cooling grows with the crown.
    assert!(number(&rows[7], "cooling_kwh") > number(&rows[1], "cooling_kwh"));
    // The utility's 4-year cycle cuts the plane at 4 and 8 for the line's clearance and the
    // regrowth before its next visit, as the utility pays per tree worked (the itemised table
    // gives no line-clearance classes, so the built-in table's price stands); the cycles
    // replace the yearly pruning line. No leaf or wood ever enters the line's minimum
    // clearance (GO 95's 18 in), and every year says how near the tree came.
    for age in [4, 8] {
        let row = &rows[age - 1];
        assert!(
            column(&header, row, "pruning").contains("line clearance"),
            "{row:?}"
        );
        assert!(
            !column(&header, row, "conflicts").contains("wire"),
            "{row:?}"
        );
        assert!(number(row, "pruning_removal_cuts") + number(row, "pruning_reduction_cuts") > 0.0);
        assert_eq!(
            number(row, "pruning_cost_usd"),
            number(row, "cost_cycles_usd") + number(row, "cost_line_clearance_utility_usd")
        );
        assert_eq!(
            number(row, "cost_line_clearance_utility_usd"),
            55.42,
            "the utility's price per tree worked: {row:?}"
        );
    }
    for row in &rows {
        assert_eq!(column(&header, row, "line_breach"), "false", "{row:?}");
        assert!(number(row, "line_closest_m") >= 0.46, "{row:?}");
    }
    assert!(rows.iter().all(|r| number(r, "cost_pruning_usd") == 0.0));
    assert_eq!(
        column(&header, &rows[1], "pruning"),
        "",
        "no cycle falls at 2"
    );
    assert_eq!(
        column(&header, &rows[2], "pruning"),
        "structural",
        "training at 3"
    );
    // Each cycle that cut is drawn before and after, its cuts ringed in blue.
    for age in ["04", "08"] {
        let p = image::open(out.join(format!("PLAC-pruned-age-{age}.png")))
            .unwrap()
            .to_rgb8();
        let blue = p
            .pixels()
            .filter(|c| c[2] > 180 && c[0] < 90 && c[1] < 120)
            .count();
        assert!(blue > 20, "{age}: {blue} blue pixels");
    }
    // The site is drawn at each year a kind of conflict first happens, with red in it.
    let pictures: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.starts_with("PLAC-site-age-"))
        .collect();
    assert!(!pictures.is_empty());
    for name in &pictures {
        let p = image::open(out.join(name)).unwrap().to_rgb8();
        let red = p
            .pixels()
            .filter(|c| c[0] > 180 && c[1] < 80 && c[2] < 80)
            .count();
        assert!(red > 50, "{name}: {red} red pixels");
    }
    let bars = image::open(out.join("PLAC-benefits.png"))
        .unwrap()
        .to_rgb8();
    assert_eq!(bars.dimensions(), (1500, 900));
    // Benefit bars up (cooling, stormwater), cost bars down (planting), each in its colour
    // in the one table of account items.
    use sylva::street::accounts::items::{Benefit, Cost};
    let count = |rgb: [u8; 3]| bars.pixels().filter(|p| p.0 == rgb).count();
    for item in [
        Benefit::Cooling.item(),
        Benefit::Stormwater.item(),
        Cost::Planting.item(),
    ] {
        let n = count(item.rgb());
        assert!(n > 500, "{}: {n} pixels", item.key);
    }
    // --json carries the same account.
    let run = sylva(&[
        "grow",
        "PLAC",
        "--from",
        "8",
        "--to",
        "8",
        "--site",
        site.to_str().unwrap(),
        "--no-pruning",
        "--no-pictures",
        "--json",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let record: serde_json::Value = serde_json::from_str(text(&run.stdout).trim()).unwrap();
    let street = &record["street"];
    assert!(street["co2_stored_kg"].as_f64().unwrap() > 0.0);
    // Never cut: no pruning, and the leader grows on into the wires' clearance.
    assert!(street["pruning"].is_null(), "{street}");
    // No --costs: the built-in sized table, no programme average; never cut, so the table's
    // own pruning ($3.90 a cm of DBH a visit, every 4 years under 15 cm, else 8) is charged.
    assert_eq!(street["cost_usd"]["average"], 0.0);
    let dbh = record["dbh_cm"].as_f64().unwrap();
    let cycle = if dbh <= 15.0 { 4.0 } else { 8.0 };
    let pruning = street["cost_usd"]["pruning"].as_f64().unwrap();
    assert!(
        (pruning - 3.90 * dbh / cycle).abs() < 0.01,
        "{pruning} at {dbh} cm"
    );
    assert!(
        street["conflicts"]
            .as_array()
            .unwrap()
            .iter()
            .any(|c| c["kind"] == "wire")
    );
}

#[test]
fn bad_sites_prices_and_costs_are_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let good = std::fs::read_to_string(repo("sites/narrow-under-wires.toml")).unwrap();
    let cases: Vec<(String, &str, Vec<&str>)> = vec![
        (good.replace("height = 8.5", "height = -1.0"), "--site", vec!["wire.height", "above the ground"]),
        (good.replace("bottom = 2.6", "bottom = -2.6"), "--site", vec!["awning.bottom"]),
        (good.replace("height = 7.0\nwidth", "height = -7.0\nwidth"), "--site", vec!["facade.height"]),
        (
            format!("{good}\n[[light]]\nx = 7.1\ny = -0.4\nheight = 6.0\nclearance = 1.0\n"),
            "--site",
            vec!["light", "apart"],
        ),
        (good.replace("voltage_kv = 12.0", "voltage = 12"), "--site", vec!["voltage"]),
        // A line's minimum clearance larger than its clearance at cutting.
        (
            good.replace("voltage_kv = 12.0", "clearance = 1.0\nminimum = 1.5"),
            "--site",
            vec!["wire.minimum", "at most the clearance"],
        ),
        // A strip of negative width: the curb on the building side of the trunk, or the
        // sidewalk starting in the roadway.
        (good.replace("curb = -0.6", "curb = 0.4"), "--site", vec!["street.curb"]),
        (
            good.replace("sidewalk = [0.6, 2.1]", "sidewalk = [-0.9, 2.1]"),
            "--site",
            vec!["street.sidewalk", "curb <= from"],
        ),
        // A mitigation whose price no cost table gives (the site asks for a root barrier).
        (
            format!("{good}\n[mitigation]\nroot_barrier_m = 6.0\n"),
            "--site",
            vec!["mitigation.root_barrier_m", "mitigation.root_barrier_per_m", "costs.toml"],
        ),
        (
            "source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nco2_per_kg = 0.05\n".into(),
            "--prices",
            vec!["stormwater_per_m3"],
        ),
        (
            "source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\nozone_per_kg = inf\nnox_per_kg = 28.2\npm10_per_kg = 20.7\nso2_per_kg = 8.2\nvoc_per_kg = 10.3\n".into(),
            "--prices",
            vec!["ozone_per_kg", "finite"],
        ),
        (COSTS.replace("planting = 200.0\n", ""), "--costs", vec!["planting"]),
        (
            COSTS.replace("[[pruning]]\nup_to_dbh_cm = 200.0", "[[pruning]]\nfrom_dbh_cm = 20.0\nup_to_dbh_cm = 200.0"),
            "--costs",
            vec!["pruning.from_dbh_cm", "no gap"],
        ),
        (
            "source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\nozone_per_kg = 1.0\nnox_per_kg = 28.2\npm10_per_kg = 20.7\nso2_per_kg = 8.2\nvoc_per_kg = 10.3\nmedian_home_price = -250000.0\n".into(),
            "--prices",
            vec!["median_home_price"],
        ),
        (
            "source = \"x\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\nozone_per_kg = 1.0\nnox_per_kg = 28.2\npm10_per_kg = 20.7\nso2_per_kg = 8.2\nvoc_per_kg = 10.3\nmedian_home_price = 250000.0\nlocation_factor = 3.0\n".into(),
            "--prices",
            vec!["location_factor"],
        ),
    ];
    for (i, (body, flag, needles)) in cases.iter().enumerate() {
        let file = dir.path().join(format!("bad-{i}.toml"));
        std::fs::write(&file, body).unwrap();
        let out = dir.path().join(format!("out-{i}"));
        let run = sylva(&[
            "grow",
            "PLAC",
            "--to",
            "3",
            flag,
            file.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        let err = text(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{flag} case {i}: {err}");
        assert!(err.contains(&format!("bad-{i}.toml")), "case {i}: {err}");
        for n in needles {
            assert!(err.contains(n), "case {i}: `{n}` not in {err}");
        }
        assert!(!out.exists(), "case {i}: nothing written");
    }
    // A survival out of range, for grow and rank alike.
    for (i, bad) in ["1.5", "0", "-0.1", "nan"].iter().enumerate() {
        let out = dir.path().join(format!("survival-{i}"));
        for command in [
            vec![
                "grow",
                "PLAC",
                "--to",
                "3",
                "--survival",
                bad,
                "-o",
                out.to_str().unwrap(),
            ],
            vec![
                "rank",
                "--years",
                "3",
                "--species",
                "PLAC",
                "--survival",
                bad,
            ],
        ] {
            let run = sylva(&command);
            let err = text(&run.stderr);
            assert_eq!(run.status.code(), Some(1), "--survival {bad}: {err}");
            assert!(
                err.contains("--survival") && err.contains("at most 1"),
                "{err}"
            );
            assert!(!out.exists(), "--survival {bad}: nothing written");
        }
    }
    // Money asked for a palm: Jenkins et al. have no group for palms.
    let prices = dir.path().join("prices.toml");
    std::fs::write(
        &prices,
        "source = \"test\"\nyear = 2024\nelectricity_per_kwh = 0.3\nnatural_gas_per_kbtu = 0.01\nstormwater_per_m3 = 2.0\nco2_per_kg = 0.05\nozone_per_kg = 11.0\nnox_per_kg = 28.2\npm10_per_kg = 20.7\nso2_per_kg = 8.2\nvoc_per_kg = 10.3\n",
    )
    .unwrap();
    let out = dir.path().join("palm");
    let run = sylva(&[
        "grow",
        "WARO",
        "--region",
        "CenFla",
        "--prices",
        prices.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let err = text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{err}");
    assert!(
        err.contains("biomass group") && err.contains("Washingtonia"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn rank_lists_a_regions_species_by_net_benefit_with_their_first_conflicts() {
    let site = repo("sites/boulevard.toml");
    let run = sylva(&[
        "rank",
        "--region",
        "InlVal",
        "--years",
        "4",
        "--site",
        site.to_str().unwrap(),
        "--json",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let rows: Vec<serde_json::Value> = text(&run.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(
        rows.len(),
        22,
        "every growable species of the Inland Valleys"
    );
    let nets: Vec<f64> = rows
        .iter()
        .map(|r| r["net_usd"].as_f64().unwrap())
        .collect();
    assert!(
        nets.windows(2).all(|w| w[0] >= w[1]),
        "best first: {nets:?}"
    );
    let ginkgo = rows.iter().find(|r| r["species"] == "GIBI").unwrap();
    assert!(
        ginkgo["not_computed"]
            .as_array()
            .unwrap()
            .iter()
            .any(|m| m.as_str().unwrap().starts_with("carbon")),
        "{ginkgo}"
    );
    assert!(
        rows.iter()
            .any(|r| !r["first_conflicts"].as_array().unwrap().is_empty())
    );
    // The site's regime (here the default standard) prunes every tree; its record is there
    // even where no cycle has cut yet, and `--no-pruning` leaves it out.
    assert!(
        rows.iter().all(|r| r["pruning"]["years"].is_array()),
        "{}",
        rows[0]
    );
    let uncut = sylva(&[
        "rank",
        "--region",
        "InlVal",
        "--years",
        "4",
        "--species",
        "PLAC",
        "--site",
        site.to_str().unwrap(),
        "--json",
        "--no-pruning",
    ]);
    assert!(uncut.status.success(), "{}", text(&uncut.stderr));
    let uncut: serde_json::Value = serde_json::from_str(text(&uncut.stdout).trim()).unwrap();
    assert!(uncut["pruning"].is_null(), "{uncut}");
    // With a site the site's own figures rank; the typical position stands beside them.
    assert!(rows.iter().all(|r| r["ranked_by"] == "this site"));
    assert!(
        rows.iter()
            .all(|r| r["site"]["net_usd"] == r["net_usd"] && r["typical"]["net_usd"].is_f64())
    );
    // Another region, no site, ranked by the typical position: every category, aesthetics
    // too, has a number for every species.
    let run = sylva(&["rank", "--region", "NoEast", "--years", "3", "--json"]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    for line in text(&run.stdout).lines() {
        let r: serde_json::Value = serde_json::from_str(line).unwrap();
        assert_eq!(r["ranked_by"], "typical position", "{r}");
        assert_eq!(r["net_usd"], r["typical"]["net_usd"], "{r}");
        let cats = r["typical"]["by_category_usd"].as_object().unwrap();
        for (name, v) in cats {
            assert!(!v.is_null(), "{name}: {r}");
        }
        // Costs by item are the one table's items, each by its key.
        let items = r["costs_by_item_usd"].as_object().unwrap();
        let keys: Vec<&str> = sylva::street::accounts::items::COSTS
            .iter()
            .map(|i| i.key)
            .collect();
        assert_eq!(items.len(), keys.len(), "{r}");
        assert!(keys.iter().all(|k| items.contains_key(*k)), "{r}");
    }
    // The site model set beside i-Tree's figures around the standard house.
    let rows = json_lines(&[
        "rank",
        "--region",
        "InlVal",
        "--calibrate",
        "--species",
        "CICA,PLAC",
        "--json",
    ]);
    assert_eq!(rows.len(), 6, "two species at 20, 30 and 40 cm");
    // The climate effect each species is held to was fitted to the other one alone: camphor's
    // is London plane's fit (`--fit --species PLAC`) times camphor's own crown projection.
    let fit = |species: &str| {
        sylva(&[
            "rank",
            "--region",
            "InlVal",
            "--calibrate",
            "--fit",
            "--species",
            species,
        ])
    };
    let run = fit("PLAC");
    assert!(run.status.success(), "{}", text(&run.stderr));
    let plac: Vec<String> = text(&run.stdout)
        .trim()
        .split(',')
        .map(String::from)
        .collect();
    // region, kWh/m², kBtu/m², useful share (none: no evergreen), points, deciduous, evergreen.
    assert_eq!(plac.len(), 7, "{plac:?}");
    assert_eq!(
        (plac[0].as_str(), plac[3].as_str(), &plac[4..]),
        (
            "InlVal",
            "",
            &["3".to_string(), "3".to_string(), "0".to_string()][..]
        )
    );
    let per_m2: f64 = plac[1].parse().unwrap();
    assert!(per_m2 > 0.0, "{plac:?}");
    for r in rows.iter().filter(|r| r["species"] == "CICA") {
        assert!(r["dbh_cm"].as_f64().unwrap() >= r["dbh_target_cm"].as_f64().unwrap());
        assert!(r["itree_natural_gas_kbtu"].as_f64().unwrap() < 0.0, "{r}");
        assert!(r["heating_in_bounds"].is_boolean());
        let expected = per_m2 * r["projection_m2"].as_f64().unwrap();
        let got = r["climate_cooling_kwh"].as_f64().unwrap();
        assert!(
            (got - expected).abs() <= 1e-3 * expected.abs() + 0.01,
            "{got} {expected} {r}"
        );
        let total = r["shade_cooling_kwh"].as_f64().unwrap() + got;
        assert!(
            (r["cooling_kwh"].as_f64().unwrap() - total).abs() < 1e-6,
            "{r}"
        );
    }
    // The Sacramento Valley's table says whose tables stand in for i-Tree's.
    let run = sylva(&[
        "rank",
        "--region",
        "SacVal",
        "--calibrate",
        "--species",
        "PLAC",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout).contains("Inland Valleys' (Modesto) tables stand in"),
        "{}",
        text(&run.stdout)
    );
    // An evergreen alone leaves nothing to fit heating to: a clear error, no row.
    let run = fit("CICA");
    assert_eq!(run.status.code(), Some(1));
    assert!(
        text(&run.stderr).contains("no deciduous broadleaf"),
        "{}",
        text(&run.stderr)
    );
    assert!(run.stdout.is_empty());
    let run = sylva(&["rank", "--calibrate", "--species", "NOPE"]);
    assert_eq!(run.status.code(), Some(1));
    assert!(
        text(&run.stderr).contains("--species NOPE"),
        "{}",
        text(&run.stderr)
    );
    let run = sylva(&["rank", "--region", "Atlantis", "--years", "4"]);
    assert_eq!(run.status.code(), Some(1));
    assert!(
        text(&run.stderr).contains("InlVal"),
        "{}",
        text(&run.stderr)
    );
}

#[test]
fn wires_quotes_the_agreement_with_the_databases_records() {
    let table =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/urban-tree-database");
    if !table.join("TS3_Raw_tree_data.csv").exists() {
        eprintln!("skipped: no TS3 beside the clone");
        return;
    }
    let run = sylva(&["wires", table.to_str().unwrap()]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let said = text(&run.stdout);
    for region in ["GulfCo", "NoEast", "MidWst"] {
        assert!(said.contains(region), "{said}");
    }
    assert!(said.contains("agreement"), "{said}");
    let run = sylva(&["wires", "/nonexistent/TS3.csv"]);
    assert_eq!(run.status.code(), Some(1));
}
