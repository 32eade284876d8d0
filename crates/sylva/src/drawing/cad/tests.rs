use super::*;
use dxf::entities::EntityType;

/// A black tupelo of two levels of stems, the second in leaf.
fn small_tree() -> crate::Skeleton {
    let mut params = crate::species::builtin("black_tupelo").unwrap();
    params.levels = 2;
    let options = crate::GenerateOptions {
        leaves: true,
        ..Default::default()
    };
    crate::generate(&params, &options).unwrap()
}

/// Every group code 5 (a handle) of a written file, with the object it names.
fn handles(text: &str) -> Vec<(String, String)> {
    let lines: Vec<&str> = text.split("\r\n").collect();
    let mut kind = String::new();
    let mut out = Vec::new();
    for two in lines.chunks_exact(2) {
        match two[0].trim() {
            "0" => kind = two[1].to_string(),
            // The header's $HANDSEED is a 5 too, in the SECTION: not an object's.
            "5" if kind != "SECTION" => out.push((kind.clone(), two[1].to_string())),
            _ => {}
        }
    }
    out
}

#[test]
fn a_generated_tree_reads_back_with_its_blocks_layers_and_units() {
    let skeleton = small_tree();
    let drawing = tree_dxf(&skeleton, "Black Tupelo").unwrap();
    let bytes = to_bytes(&drawing).unwrap();
    let back = Drawing::load(&mut bytes.as_slice()).unwrap();
    let names: Vec<String> = back.blocks().map(|b| b.name.clone()).collect();
    for view in ["PLAN", "FRONT", "SIDE"] {
        assert!(names.contains(&format!("Black_Tupelo-{view}")), "{names:?}");
    }
    let layers: Vec<String> = back.layers().map(|l| l.name.clone()).collect();
    for (layer, _) in LAYERS {
        assert!(layers.iter().any(|l| l == layer), "{layers:?}");
    }
    assert_eq!(back.header.default_drawing_units, Units::Meters);
    let inserts = (back.entities())
        .filter(|e| matches!(e.specific, EntityType::Insert(_)))
        .count();
    assert_eq!(inserts, 3);
    // The front elevation is as tall as the tree.
    let front = back.blocks().find(|b| b.name.ends_with("-FRONT")).unwrap();
    let top = (front.entities.iter())
        .filter_map(|e| match &e.specific {
            EntityType::Line(l) => Some(l.p1.y.max(l.p2.y)),
            EntityType::LwPolyline(p) => p.vertices.iter().map(|v| v.y).reduce(f64::max),
            _ => None,
        })
        .fold(0.0f64, f64::max);
    let stats = skeleton.stats();
    assert!(
        (top / f64::from(stats.height) - 1.0).abs() < 0.05,
        "front elevation {top:.2} m, tree {:.2} m",
        stats.height
    );
    // Leaves are drawn in the elevations, not in plan.
    let plan = back.blocks().find(|b| b.name.ends_with("-PLAN")).unwrap();
    assert!(
        !plan
            .entities
            .iter()
            .any(|e| e.common.layer == "TREE-LEAVES")
    );
    assert!(
        front
            .entities
            .iter()
            .any(|e| e.common.layer == "TREE-LEAVES")
    );
}

#[test]
fn every_object_has_a_handle_of_its_own_and_the_same_tree_the_same_bytes() {
    let skeleton = small_tree();
    let a = to_bytes(&tree_dxf(&skeleton, "t").unwrap()).unwrap();
    let b = to_bytes(&tree_dxf(&skeleton, "t").unwrap()).unwrap();
    assert!(a == b, "two writes of one tree differ");
    let text = String::from_utf8(a).unwrap();
    let all = handles(&text);
    let mut seen = std::collections::HashMap::new();
    for (kind, h) in &all {
        if let Some(before) = seen.insert(h.clone(), kind.clone()) {
            panic!("handle {h} is {before}'s and {kind}'s");
        }
    }
    // Every table, and every ENDBLK, has one (the crate gives neither its own).
    let tables = text.matches("\r\nTABLE\r\n").count();
    assert!(tables >= 7, "{tables}");
    assert_eq!(all.iter().filter(|(k, _)| k == "TABLE").count(), tables);
    let endblk = text.matches("\r\nENDBLK\r\n").count();
    assert_eq!(all.iter().filter(|(k, _)| k == "ENDBLK").count(), endblk);
    // $HANDSEED lies past every handle.
    let seed = text.split("$HANDSEED\r\n  5\r\n").nth(1).unwrap();
    let seed = u64::from_str_radix(seed.split("\r\n").next().unwrap(), 16).unwrap();
    let max = (all.iter())
        .map(|(_, h)| u64::from_str_radix(h, 16).unwrap())
        .max()
        .unwrap();
    assert!(seed > max, "$HANDSEED {seed:X}, a handle {max:X}");
    // Entities inside blocks, and in model space, name their owner.
    let owned = text.matches("\r\nLINE\r\n  5\r\n").count();
    let lines_with_owner = (text.split("\r\n  0\r\nLINE\r\n").skip(1))
        .filter(|o| {
            o.split("\r\n  0\r\n")
                .next()
                .unwrap()
                .contains("\r\n330\r\n")
        })
        .count();
    assert_eq!(owned, lines_with_owner);
}

#[test]
fn a_planting_plan_places_each_tree_on_its_species_layer_scaled_and_turned() {
    let symbol = PlanSymbol::of(&small_tree());
    assert!(symbol.crown.len() >= 3 && symbol.trunk_radius > 0.0);
    let mut plan = PlantingPlan::new(Units::Feet, 0.3048);
    let layer = plan.layer("TREE-NYSY Nyssa sylvatica", 3);
    let block = plan.symbol("NYSY-InlVal-30-0", &symbol);
    plan.place(
        &block,
        &layer,
        (1000.0, 2000.0),
        0.5,
        std::f64::consts::FRAC_PI_2,
    )
    .unwrap();
    plan.place(&block, &layer, (1030.0, 2000.0), 1.0, 0.0)
        .unwrap();
    assert_eq!(plan.inserts(), 2);
    let bytes = plan.to_bytes().unwrap();
    let back = Drawing::load(&mut bytes.as_slice()).unwrap();
    assert_eq!(back.header.default_drawing_units, Units::Feet);
    let inserts: Vec<_> = (back.entities())
        .filter_map(|e| match &e.specific {
            EntityType::Insert(i) => Some((e.common.layer.clone(), i.clone())),
            _ => None,
        })
        .collect();
    assert_eq!(inserts.len(), 2);
    assert_eq!(inserts[0].1.name, "NYSY-InlVal-30-0");
    // Half the grown tree, in feet.
    assert!((inserts[0].1.x_scale_factor - 0.5 / 0.3048).abs() < 1e-9);
    assert!((inserts[0].1.rotation - 90.0).abs() < 1e-9);
    assert_eq!(inserts[1].1.location.x, 1030.0);
    assert_eq!(inserts[0].0, "TREE-NYSY Nyssa sylvatica");
    let b = back
        .blocks()
        .find(|b| b.name == "NYSY-InlVal-30-0")
        .unwrap();
    assert!(b.entities.iter().all(|e| e.common.layer == "0"));
}

#[test]
fn a_grown_trees_plan_symbol_is_as_wide_as_its_measured_crown() {
    let plane = crate::growth::Database::builtin()
        .find("InlVal", "PLAC")
        .unwrap();
    let skeleton = crate::growth::survey::report::Cohort::new(vec![plane], 0)
        .advance_to(15.0)
        .remove(0);
    let symbol = PlanSymbol::of(&skeleton);
    let (lo, hi) = symbol.crown.iter().fold(
        (Vec2::splat(f32::MAX), Vec2::splat(f32::MIN)),
        |(lo, hi), p| (lo.min(Vec2::from_array(*p)), hi.max(Vec2::from_array(*p))),
    );
    let width = (hi - lo).element_sum() / 2.0;
    let measured = crate::growth::measure(&skeleton).crown_diameter as f32;
    assert!(
        (width / measured - 1.0).abs() < 0.1,
        "plan symbol {width:.2} m across, crown {measured:.2} m"
    );
    // The trunk stands at the symbol's origin, its radius the grown trunk's at the ground.
    assert!(Vec2::from_array(symbol.trunk).length() < 0.05);
    assert!(symbol.trunk_radius > 0.02 && symbol.trunk_radius < 0.5);
}

#[test]
fn a_plan_past_its_budget_is_refused() {
    let e = over_budget(MAX_INSERTS + 1).to_string();
    assert!(e.contains("250000") && e.contains("smaller"), "{e}");
}

#[test]
fn the_hull_of_a_square_and_its_centre_is_the_square() {
    let h = hull(vec![
        Vec2::ZERO,
        Vec2::X,
        Vec2::ONE,
        Vec2::Y,
        Vec2::splat(0.5),
    ]);
    assert_eq!(h.len(), 4);
}
