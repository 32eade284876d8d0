//! A street tree on its site, captioned as `sylva grow --site` writes it: the year it first
//! runs into each kind of fixture, and each pruning cycle before and after the cuts. The
//! drawing itself is the library's (`sylva::street::picture`); this adds the words.

use crate::caption::with_caption;
use crate::street::tree_picture;
use crate::{Picture, RenderError, Renderer};
use sylva::Skeleton;
use sylva::growth::survey::report::{AgeRecord, age_label};
use sylva::growth::{CutKind, Dress, Measured};
use sylva::mesh::TreeMesh;
use sylva::street::accounts::pruner::PruningYear;
use sylva::street::picture::{pruning_picture, site_picture};
use sylva::street::work::conflicts::conflicts;
use sylva::street::{Conflict, Kind, Site};

/// Captions' text size, pixels.
const TEXT: f32 = 18.0;

fn picture((width, height, rgba): (u32, u32, Vec<u8>)) -> Picture {
    Picture {
        width,
        height,
        rgba,
        stats: Default::default(),
    }
}

/// Species `m` at `age` on `site`, across the street and from above, with the conflicts met
/// for the first time that year (`new`) marked and named.
pub fn first_conflicts_picture(
    m: &Measured,
    age: f64,
    skeleton: &Skeleton,
    site: &Site,
    new: &[Conflict],
    size: (u32, u32),
) -> Picture {
    let kinds: Vec<Kind> = new.iter().map(|c| c.kind).collect();
    let drawn = picture(site_picture(skeleton, site, &kinds, size));
    let said: Vec<String> = new.iter().map(|c| c.describe()).collect();
    let lines = [
        format!(
            "{}, age {}: first {}",
            m.label(),
            age_label(age),
            said.join(", ")
        ),
        "left: across the street; right: from above (bar: 5 m); a 1.8 m person".to_string(),
        "red: in the way; red outline: the zone entered this year; shaded: clear heights; \
         circles: a line's clearance at cutting (grey) and its minimum (dark red), a lamp's \
         clearance (yellow); grey band: the line's clearance from above"
            .to_string(),
    ];
    with_caption(&drawn, &lines, TEXT)
}

/// A pruning cycle of species `m` in `year`: the tree across the street before the year's
/// cuts (`before`) and after them (`after`), the cuts ringed, with what they took and cost.
pub fn pruning_cycle_picture(
    m: &Measured,
    year: f64,
    cycle: &PruningYear,
    before: &Skeleton,
    after: &Skeleton,
    site: &Site,
    size: (u32, u32),
) -> Picture {
    let drawn = picture(pruning_picture(before, after, site, cycle.marks(), size));
    let left: Vec<Kind> = conflicts(after, site).iter().map(|c| c.kind).collect();
    let kinds = |k: &[Kind]| {
        let names: Vec<&str> = k.iter().map(|k| k.name()).collect();
        if names.is_empty() {
            "none".to_string()
        } else {
            names.join(", ")
        }
    };
    let reasons: Vec<&str> = cycle.reasons.iter().map(|r| r.name()).collect();
    let lines = [
        format!(
            "{}, age {}: {}: {} removal, {} reduction{} cuts (largest {:.0} cm across), \
             {:.1} m2 of leaf and {:.3} m3 of wood taken, {} visit(s), ${:.2}",
            m.label(),
            age_label(year),
            reasons.join(", "),
            cycle.count(CutKind::Removal),
            cycle.count(CutKind::Reduction),
            match cycle.count(CutKind::Heading) {
                0 => String::new(),
                n => format!(" and {n} heading"),
            },
            100.0 * cycle.cuts.largest_diameter(),
            cycle.leaf_m2(),
            cycle.wood_m3(),
            cycle.visits,
            cycle.cost
        ),
        format!(
            "in the way before the cuts: {}; after: {}{}",
            kinds(&cycle.before),
            kinds(&left),
            if cycle.cuts.left_in_zone {
                " (a trunk with no lateral to cut back to is left)"
            } else {
                ""
            }
        ),
        "left: before the cuts; right: after, at one scale; blue rings: the cuts; red: in the \
         way; circles: a line's clearance at cutting (grey) and its minimum (dark red), a \
         lamp's clearance (yellow); a 1.8 m person"
            .to_string(),
    ];
    with_caption(&drawn, &lines, TEXT)
}

/// A grown street tree at an age in the run's frame (`extent`), captioned with its height
/// beside the equations' and its crown (`when`: `" in winter"`, or empty).
pub fn grown_tree_picture(
    r: &Renderer,
    (mesh, dress): (&TreeMesh, &Dress),
    m: &Measured,
    record: &AgeRecord,
    when: &str,
    size: (u32, u32),
    extent: (f64, f64),
) -> Result<Picture, RenderError> {
    let picture = tree_picture(r, mesh, dress, size, extent)?;
    let lines = [format!(
        "{}, age {}{when}: height {:.1} m (measured {:.1}), crown {:.1} m",
        m.label(),
        age_label(record.age),
        record.model.height,
        record.measured.height,
        record.model.crown_diameter
    )];
    Ok(with_caption(&picture, &lines, TEXT))
}
