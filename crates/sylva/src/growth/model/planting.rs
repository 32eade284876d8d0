//! The sapling as planted: the nursery's years before the species' first fitted age, its
//! stems raised (one leader, or a multi-stem tree's several), its first buds set.

use super::*;

impl Grower {
    /// A sapling of the species, `NURSERY_YEARS` before its first fitted age, brought up to
    /// that age.
    pub fn new(measured: Measured, options: GrowthOptions) -> Self {
        let mut g = Self::sapling(measured, options);
        let first = g.measured.ages.0;
        g.advance_to(first);
        g
    }

    /// The sapling `NURSERY_YEARS` before the first fitted age: a trunk alone.
    pub(crate) fn sapling(measured: Measured, options: GrowthOptions) -> Self {
        let habit = habit_of(&measured.species.code, &measured.species.tree_type);
        // Metamers in proportion to the grown crown: a large tree's shoots carry longer
        // internodes, and the segment budget goes as far.
        let grown = measured.crown_diameter(measured.ages.1) as f32;
        let metamer = (grown / 40.0).clamp(0.12, 0.35);
        let fork_height = measured.crown_base(measured.ages.1).max(1.5) as f32;
        let conifer = measured.species.tree_type.starts_with('C');
        // A conifer's "leaf" is a tuft or bundle of needles, set far closer along the shoot
        // than a broadleaf's leaves. Species of the foliage table wear their own leaves;
        // the others a 14 x 10 cm oval or a needle tuft.
        let (generic, spacing) = if conifer {
            (((0.12, 0.03), LeafShape::Palm), 0.004)
        } else {
            (((0.14, 0.1), LeafShape::Oval), 0.012)
        };
        let own = foliage::of(&measured.species.code);
        let (leaf_size, leaf_shape) = own.map_or(generic, |f| (f.leaf_size(), f.shape()));
        let leaf_spacing = spacing;
        // Small or finely cut leaves cost more vertices per square metre of leaf than the
        // generic one; past their allowance they are drawn larger (and fewer), so a
        // species' model stays about the size of the generic tree's.
        let ((gl, gw), gs) = generic;
        // (The generic leaf itself is never capped: its trees grow as they always have.)
        let leaf_vertex_cap = own.map(|_| {
            let generic_area = gl * gw * crate::mesh::leaf_template(gs).area();
            (
                leaf_vertex_allowance(leaf_shape) * vertices_per_area(gl, gw, gs),
                generic_area,
            )
        });
        // Refitted to the tree's bounds every step: cells outside a crown are empty, so
        // light there needs no walking.
        let light = LightGrid::new(Vec3::ZERO, Vec3::ONE, options.light_cell, MAX_LIGHT_CELLS);
        let key = StreamKey::from_seed(options.seed);
        let start = measured.ages.0 - NURSERY_YEARS;
        let mut g = Grower {
            habit,
            age: start,
            rng: key.child(1).stream(),
            key,
            branches: Vec::new(),
            segments: Vec::new(),
            light,
            sky: daylight(),
            vigour: 2.0,
            spread: 1.0,
            metamer,
            fork_height,
            lobes: {
                let mut r = key.child(2).stream();
                [0; 3].map(|_| (r.unit() * std::f64::consts::TAU) as f32)
            },
            buds: Vec::new(),
            sprouting: sprouts::sprouting(
                &measured.species.scientific,
                &measured.species.tree_type,
            ),
            short_shoots: Vec::new(),
            leaf_size,
            leaf_shape,
            leaf_vertex_cap,
            leaf_spacing,
            leaves_on: Vec::new(),
            radii: Vec::new(),
            tip_radius: 0.001,
            leaf_boost: 1.0,
            leaf_reach: LEAF_REACH,
            regrowth: None,
            cut_top: None,
            made: (0, 0),
            dropped_branches: 0,
            young_year: true,
            times: StepTimes::default(),
            options,
            measured,
        };
        let t = g.targets(start);
        let stems = if g.habit.form == TreeForm::Palm {
            1
        } else {
            g.habit.stems.max(1)
        };
        // The trunk: order 0, one segment, growing straight up; on a multi-stem tree only
        // its collar, from which the stems rise.
        let trunk = if stems > 1 {
            STEM_COLLAR
        } else {
            t.height as f32
        };
        let id = g.next_branch_id();
        g.branches.push(Branch {
            id,
            order: 0,
            rank: 0,
            parent: None,
            segments: vec![0],
            next_azimuth: 0.0,
            alive: true,
            children: Vec::new(),
            finished: 0.0,
            offset: 0.0,
            anchor: 0.0,
            shaded_years: 0,
            headed: false,
            sprung: false,
        });
        let id = g.next_segment_id();
        g.segments.push(Segment {
            id,
            branch: 0,
            start: Vec3::ZERO,
            direction: Vec3::Z,
            length: trunk,
            goal: trunk,
            born: start,
        });
        if stems > 1 {
            g.raise_stems(stems, t.height as f32);
        } else {
            g.set_buds(0, 0);
        }
        g.refresh_radii();
        g.update_light();
        g.young_year = g.young_year();
        g
    }

    /// A multi-stem tree's `n` stems, rising from the trunk's collar to `height`: order-0
    /// axes like the trunk (never shed, not counted in the crown, read together for DBH),
    /// spread evenly around it and leaning out by `STEM_LEAN`.
    fn raise_stems(&mut self, n: u8, height: f32) {
        let collar = Vec3::new(0.0, 0.0, STEM_COLLAR);
        let lean = STEM_LEAN.to_radians();
        let length = ((height - STEM_COLLAR) / lean.cos()).max(0.05);
        let turn = self.rng.unit() as f32 * std::f32::consts::TAU;
        for k in 0..n {
            let azimuth = turn + k as f32 * std::f32::consts::TAU / n as f32;
            let direction = Vec3::new(
                lean.sin() * azimuth.cos(),
                lean.sin() * azimuth.sin(),
                lean.cos(),
            );
            let id = self.branches.len() as u32;
            self.branches[0].children.push(id);
            let branch_id = self.next_branch_id();
            self.branches.push(Branch {
                id: branch_id,
                order: 0,
                rank: 0,
                parent: Some((0, 0)),
                segments: vec![self.segments.len() as u32],
                next_azimuth: (self.rng.unit() * 360.0) as f32,
                alive: true,
                children: Vec::new(),
                finished: 0.0,
                offset: STEM_COLLAR,
                anchor: 0.0,
                shaded_years: 0,
                headed: false,
                sprung: false,
            });
            let segment_id = self.next_segment_id();
            self.segments.push(Segment {
                id: segment_id,
                branch: id,
                start: collar,
                direction,
                length,
                goal: length,
                born: self.age,
            });
            self.set_buds(id as usize, self.segments.len() as u32 - 1);
        }
    }
}
