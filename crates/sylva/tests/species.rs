//! The built-in species are what they are named: real sizes and the structure that defines
//! each form, measured on the generated skeletons (several seeds each).

use sylva::{GenerateOptions, Skeleton, generate, species::builtin};

fn trees(id: &str) -> Vec<Skeleton> {
    let p = builtin(id).unwrap_or_else(|| panic!("no built-in {id}"));
    (0..3)
        .map(|seed| {
            generate(
                &p,
                &GenerateOptions {
                    seed,
                    ..Default::default()
                },
            )
            .unwrap()
        })
        .collect()
}

fn trunks(sk: &Skeleton) -> usize {
    sk.stems
        .iter()
        .filter(|s| s.level == 0 && s.clone_of.is_none())
        .count()
}

#[test]
fn there_are_twelve_species_covering_plate_1() {
    let ids: Vec<_> = sylva::species::builtin_ids().collect();
    assert!(ids.len() >= 12, "{ids:?}");
    for id in [
        "balsam_fir",
        "austrian_pine",
        "queen_palm",
        "saguaro",
        "hazel",
        "lombardy_poplar",
        "golden_bamboo",
        "weeping_birch",
    ] {
        assert!(ids.contains(&id), "{id}");
    }
}

#[test]
fn balsam_fir_is_a_narrow_cone_branched_to_the_ground() {
    for sk in trees("balsam_fir") {
        let s = sk.stats();
        assert!((12.0..=22.0).contains(&s.height), "height {}", s.height);
        assert!(
            s.crown_width / s.height < 0.55,
            "crown {} for height {}",
            s.crown_width,
            s.height
        );
        let lowest = sk
            .stems
            .iter()
            .filter(|st| st.level == 1)
            .map(|st| st.offset)
            .fold(f32::MAX, f32::min);
        assert!(lowest < 0.1 * s.height, "lowest branch at {lowest} m");
    }
}

#[test]
fn austrian_pine_has_a_bare_trunk_and_needle_tufts() {
    for sk in trees("austrian_pine") {
        let s = sk.stats();
        assert!((18.0..=32.0).contains(&s.height), "height {}", s.height);
        let lowest = sk
            .stems
            .iter()
            .filter(|st| st.level == 1)
            .map(|st| st.offset)
            .fold(f32::MAX, f32::min);
        assert!(
            lowest > 0.4 * sk.stems[0].length,
            "branches start at {lowest} m"
        );
        assert!(s.leaves > 10_000);
    }
}

#[test]
fn queen_palm_is_an_unbranched_trunk_with_a_crown_of_fronds() {
    for sk in trees("queen_palm") {
        let s = sk.stats();
        assert!((9.0..=17.0).contains(&s.height), "height {}", s.height);
        assert_eq!(s.stems_per_level.len(), 2);
        let fronds = s.stems_per_level[1];
        assert!((12..=18).contains(&fronds), "{fronds} fronds");
        let l0 = sk.stems[0].length;
        assert!(
            sk.stems
                .iter()
                .filter(|st| st.level == 1)
                .all(|st| st.offset > 0.9 * l0)
        );
        // Fronds arch: their tips hang below their highest point.
        let arching = sk
            .stems
            .iter()
            .enumerate()
            .filter(|(_, st)| st.level == 1)
            .filter(|(i, _)| {
                let secs = sk.sections_of(sylva::StemId(*i as u32));
                let top = secs.iter().map(|c| c.position.z).fold(f32::MIN, f32::max);
                secs.last().unwrap().position.z < top - 0.3
            });
        assert!(arching.count() >= fronds / 2);
    }
}

#[test]
fn saguaro_is_a_ribbed_column_with_upturned_arms() {
    for sk in trees("saguaro") {
        let s = sk.stats();
        assert!((6.0..=13.0).contains(&s.height), "height {}", s.height);
        assert_eq!(s.leaves, 0);
        assert!(sk.stems[0].lobes >= 10, "ribs");
        for (i, arm) in sk.stems.iter().enumerate().filter(|(_, st)| st.level == 1) {
            let secs = sk.sections_of(sylva::StemId(i as u32));
            let tip = secs.last().unwrap().orientation * glam::Vec3::Z;
            assert!(tip.z > 0.5, "arm {i} ends pointing up ({tip})");
            assert!(arm.length > 1.0);
        }
        // Periodic taper: the trunk's radius rises and falls along its length.
        let radii: Vec<f32> = sk
            .sections_of(sylva::StemId(0))
            .iter()
            .map(|c| c.radius)
            .collect();
        let turns = radii
            .windows(3)
            .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
            .count();
        assert!(turns >= 6, "{turns} bead turns");
    }
}

#[test]
fn hazel_is_a_shrub_of_several_stems_from_the_ground() {
    for sk in trees("hazel") {
        let s = sk.stats();
        assert!((2.5..=7.0).contains(&s.height), "height {}", s.height);
        assert!(trunks(&sk) >= 6);
        assert!(sk.stems.iter().filter(|st| st.level == 0).all(|st| {
            sk.sections[st.sections.start as usize].position.z.abs() < 1e-3 || st.clone_of.is_some()
        }));
    }
}

#[test]
fn lombardy_poplar_is_columnar() {
    for sk in trees("lombardy_poplar") {
        let s = sk.stats();
        assert!((20.0..=32.0).contains(&s.height), "height {}", s.height);
        assert!(
            s.crown_width / s.height < 0.3,
            "crown {} for height {}",
            s.crown_width,
            s.height
        );
    }
}

#[test]
fn golden_bamboo_is_a_clump_of_culms() {
    for sk in trees("golden_bamboo") {
        let s = sk.stats();
        assert!((4.5..=10.5).contains(&s.height), "height {}", s.height);
        assert!(trunks(&sk) >= 10);
        assert!(
            sk.stems
                .iter()
                .filter(|st| st.level == 0)
                .all(|st| sk.sections[st.sections.start as usize].radius < 0.08)
        );
    }
}

#[test]
fn weeping_birch_hangs_its_twigs() {
    for sk in trees("weeping_birch") {
        let s = sk.stats();
        assert!((3.5..=9.0).contains(&s.height), "height {}", s.height);
        let twigs: Vec<_> = sk
            .stems
            .iter()
            .enumerate()
            .filter(|(_, st)| st.level == 2)
            .collect();
        let hanging = twigs
            .iter()
            .filter(|(i, _)| {
                let secs = sk.sections_of(sylva::StemId(*i as u32));
                (secs.last().unwrap().orientation * glam::Vec3::Z).z < -0.5
            })
            .count();
        assert!(
            hanging * 10 >= twigs.len() * 7,
            "{hanging} of {} twigs hang",
            twigs.len()
        );
    }
}
