//! The parameter panel: every parameter of the table, grouped by level, each with its
//! documented range and meaning as a tooltip.

use eframe::egui;
use sylva::TreeParams;
use sylva::params::{LEVEL_SETS, PARAMS, ParamDef, ParamKind};

/// Shows one control per parameter; returns true when any value changed.
pub fn parameters(ui: &mut egui::Ui, params: &mut TreeParams) -> bool {
    let mut changed = false;
    egui::CollapsingHeader::new("Tree")
        .default_open(true)
        .show(ui, |ui| {
            for def in PARAMS.iter().filter(|d| !d.per_level && !is_leaf(d)) {
                changed |= control(ui, params, def, 0);
            }
        });
    for level in 0..LEVEL_SETS {
        let title = if level == 0 {
            "Trunk (level 0)".to_string()
        } else {
            format!("Level {level}")
        };
        egui::CollapsingHeader::new(title).show(ui, |ui| {
            for def in PARAMS
                .iter()
                .filter(|d| d.per_level && d.levels().contains(&level))
            {
                changed |= control(ui, params, def, level);
            }
        });
    }
    egui::CollapsingHeader::new("Leaves")
        .default_open(true)
        .show(ui, |ui| {
            for def in PARAMS.iter().filter(|d| is_leaf(d)) {
                changed |= control(ui, params, def, 0);
            }
        });
    changed
}

fn is_leaf(def: &ParamDef) -> bool {
    def.name.starts_with("Leaf") || def.name == "Leaves"
}

/// A slider over the documented range, or a drag value for ranges too wide to slide.
fn control(ui: &mut egui::Ui, params: &mut TreeParams, def: &ParamDef, level: usize) -> bool {
    let name = def.name_at(level);
    let mut value = (def.get)(params, level);
    let before = value;
    ui.horizontal(|ui| {
        ui.label(&name)
            .on_hover_text(format!("{} [{}], {}", def.doc, def.unit, def.range_text()));
        // Sliders over the whole documented range (up to 100000) would be useless for the usual
        // values; wide ranges get a slider over a practical span plus a drag value beyond.
        let (lo, hi) = practical_range(def);
        let integer = def.kind == ParamKind::Integer;
        let slider = egui::Slider::new(&mut value, lo..=hi).clamping(egui::SliderClamping::Never);
        let slider = if integer { slider.integer() } else { slider };
        ui.add(slider);
    });
    value = value.clamp(def.min, def.max);
    if def.kind == ParamKind::Integer {
        value = value.round();
    }
    if value != before && def.check(&name, value).is_ok() {
        (def.set)(params, level, value);
        return true;
    }
    false
}

fn practical_range(def: &ParamDef) -> (f64, f64) {
    let lo = def.min.max(-360.0);
    let hi = match def.name {
        "Branches" | "Leaves" => 300.0,
        "CurveRes" => 30.0,
        "Scale" | "ScaleV" => 60.0,
        "0Branches" => 40.0,
        "0BranchDist" => 10.0,
        "Length" | "LengthV" | "ZScale" | "ZScaleV" | "0Scale" | "0ScaleV" => 3.0,
        "Lobes" => 16.0,
        "LobeDepth" | "Flare" => 3.0,
        "SegSplits" | "0BaseSplits" => 5.0,
        "LeafScale" | "LeafScaleX" | "PruneWidth" => 2.0,
        "LeafQuality" => 4.0,
        "LeafStemLen" => 5.0,
        "AttractionUp" => 10.0,
        "RatioPower" => 4.0,
        "Ratio" => 0.1,
        "PrunePowerLow" | "PrunePowerHigh" => 5.0,
        _ => def.max.min(360.0),
    };
    let lo = match def.name {
        "Leaves" | "Branches" => -20.0,
        "LeafStemLen" => -5.0,
        "AttractionUp" => -10.0,
        "RatioPower" => -2.0,
        _ => lo,
    };
    (lo.max(def.min), hi.min(def.max))
}
