//! Carbon a street tree stores and takes up each year, from its trunk diameter.
//!
//! Above-ground dry biomass follows Jenkins, Chojnacky, Heath & Birdsey (2003), "National-scale
//! biomass estimators for United States tree species", Forest Science 49(1):12-35, Table 4:
//! `biomass_kg = exp(b0 + b1 ln dbh_cm)`, with one pair of coefficients per national species
//! group. The group is chosen by genus (Jenkins' own assignment of genera to groups); a genus
//! the paper does not place (palms, Ginkgo, Cedrus, Podocarpus...) has no group, and its carbon
//! is reported as missing rather than borrowed from another group.
//!
//! The rest follows i-Tree's urban practice: open-grown urban trees carry less wood than the
//! forest trees the equations were fitted to, so biomass is multiplied by 0.8 (Nowak 1994,
//! "Atmospheric carbon dioxide reduction by Chicago's urban forest", USDA GTR NE-186, p. 83-94);
//! roots add a root:shoot ratio of 0.26 (Cairns, Brown, Helmer & Baumgardner 1997, Oecologia
//! 111:1-11, the mean for upland forests); carbon is half the dry weight; CO2 is carbon times
//! 44/12.

/// Jenkins et al. (2003) species groups.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BiomassGroup {
    /// Aspen, alder, cottonwood, willow.
    AspenAlderCottonwoodWillow,
    /// Soft maple and birch.
    SoftMapleBirch,
    /// Mixed hardwood: every hardwood genus not in another group.
    MixedHardwood,
    /// Hard maple, oak, hickory, beech.
    HardMapleOakHickoryBeech,
    /// Cedar and larch.
    CedarLarch,
    /// Douglas-fir.
    DouglasFir,
    /// True fir and hemlock.
    TrueFirHemlock,
    /// Pine.
    Pine,
    /// Spruce.
    Spruce,
    /// Woodland species: juniper, woodland oak, mesquite.
    Woodland,
}

impl BiomassGroup {
    /// `(b0, b1)` of Jenkins et al. (2003) Table 4.
    pub fn coefficients(self) -> (f64, f64) {
        use BiomassGroup::*;
        match self {
            AspenAlderCottonwoodWillow => (-2.2094, 2.3867),
            SoftMapleBirch => (-1.9123, 2.3651),
            MixedHardwood => (-2.4800, 2.4835),
            HardMapleOakHickoryBeech => (-2.0127, 2.4342),
            CedarLarch => (-2.0336, 2.2592),
            DouglasFir => (-2.2304, 2.4435),
            TrueFirHemlock => (-2.5384, 2.4814),
            Pine => (-2.5356, 2.4349),
            Spruce => (-2.0773, 2.3323),
            Woodland => (-0.7152, 1.7029),
        }
    }

    /// The group's name as Jenkins et al. write it.
    pub fn name(self) -> &'static str {
        use BiomassGroup::*;
        match self {
            AspenAlderCottonwoodWillow => "aspen/alder/cottonwood/willow",
            SoftMapleBirch => "soft maple/birch",
            MixedHardwood => "mixed hardwood",
            HardMapleOakHickoryBeech => "hard maple/oak/hickory/beech",
            CedarLarch => "cedar/larch",
            DouglasFir => "Douglas-fir",
            TrueFirHemlock => "true fir/hemlock",
            Pine => "pine",
            Spruce => "spruce",
            Woodland => "woodland",
        }
    }

    /// The group of a species by its scientific name, or `None` where Jenkins et al. place no
    /// such genus.
    pub fn of(scientific: &str) -> Option<BiomassGroup> {
        use BiomassGroup::*;
        let mut words = scientific.split_whitespace();
        let genus = words.next()?;
        let epithet = words.next().unwrap_or("");
        Some(match genus {
            "Populus" | "Alnus" | "Salix" => AspenAlderCottonwoodWillow,
            // Jenkins put sugar and black maple with the oaks; every other maple is soft.
            "Acer" if matches!(epithet, "saccharum" | "nigrum") => HardMapleOakHickoryBeech,
            "Acer" | "Betula" => SoftMapleBirch,
            "Quercus" | "Carya" | "Fagus" => HardMapleOakHickoryBeech,
            "Juniperus" | "Prosopis" => Woodland,
            // Cypress-family conifers (incense cedar, arborvitae, redwood) and larch.
            "Thuja" | "Chamaecyparis" | "Calocedrus" | "Larix" | "Platycladus" | "Sequoia"
            | "Cupressus" => CedarLarch,
            "Pseudotsuga" => DouglasFir,
            "Abies" | "Tsuga" => TrueFirHemlock,
            "Pinus" => Pine,
            "Picea" => Spruce,
            // Jenkins' residual group holds every other dicot hardwood; these genera are
            // conifers, a gymnosperm (Ginkgo) or palms, which no group covers.
            "Ginkgo" | "Cedrus" | "Podocarpus" | "Phoenix" | "Washingtonia" | "Sabal"
            | "Syagrus" | "Butia" | "Cocos" | "Veitchia" => return None,
            _ => MixedHardwood,
        })
    }
}

/// Share of an urban tree's biomass the forest equations predict (Nowak 1994).
pub const URBAN_FACTOR: f64 = 0.8;
/// Below-ground biomass per unit above-ground (Cairns et al. 1997).
pub const ROOT_SHOOT: f64 = 0.26;
/// Carbon per unit dry biomass.
pub const CARBON_FRACTION: f64 = 0.5;
/// kg CO2 per kg carbon (molar masses 44 and 12).
pub const CO2_PER_C: f64 = 44.0 / 12.0;

/// CO2 taken up in the year that ends at `age` by a tree of `dbh_cm` grown as `m`, kg, with
/// no record of last year: last year's DBH from the measured growth, in proportion, so that a
/// grown tree slightly off the curve is not penalised.
pub fn co2_sequestered_kg(
    group: BiomassGroup,
    m: &crate::growth::Measured,
    age: f64,
    dbh_cm: f64,
) -> f64 {
    let previous = (age - 1.0).max(m.ages.0);
    let ratio = if m.dbh(age) > 0.0 {
        m.dbh(previous) / m.dbh(age)
    } else {
        0.0
    };
    co2_stored_kg(group, dbh_cm) - co2_stored_kg(group, dbh_cm * ratio.min(1.0))
}

/// CO2 a tree of `dbh_cm` holds, kg: above and below ground, urban-adjusted.
pub fn co2_stored_kg(group: BiomassGroup, dbh_cm: f64) -> f64 {
    if dbh_cm.is_nan() || dbh_cm <= 0.0 {
        return 0.0;
    }
    let (b0, b1) = group.coefficients();
    let above = (b0 + b1 * dbh_cm.ln()).exp();
    above * URBAN_FACTOR * (1.0 + ROOT_SHOOT) * CARBON_FRACTION * CO2_PER_C
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jenkins_mixed_hardwood_at_30_cm() {
        // exp(-2.48 + 2.4835 ln 30) = 390.3 kg above ground; x0.8 x1.26 x0.5 x44/12.
        let above = (-2.48f64 + 2.4835 * 30f64.ln()).exp();
        assert!((above - 390.3).abs() < 0.1, "{above}");
        let co2 = co2_stored_kg(BiomassGroup::MixedHardwood, 30.0);
        assert!((co2 - above * 0.8 * 1.26 * 0.5 * 44.0 / 12.0).abs() < 1e-9);
        assert!((co2 - 721.2).abs() < 0.1, "{co2}");
    }

    #[test]
    fn groups_by_genus() {
        assert_eq!(
            BiomassGroup::of("Platanus x acerifolia"),
            Some(BiomassGroup::MixedHardwood)
        );
        assert_eq!(
            BiomassGroup::of("Acer saccharum"),
            Some(BiomassGroup::HardMapleOakHickoryBeech)
        );
        assert_eq!(
            BiomassGroup::of("Acer saccharinum"),
            Some(BiomassGroup::SoftMapleBirch)
        );
        assert_eq!(
            BiomassGroup::of("Pinus thunbergiana"),
            Some(BiomassGroup::Pine)
        );
        assert_eq!(BiomassGroup::of("Washingtonia robusta"), None);
        assert_eq!(BiomassGroup::of("Ginkgo biloba"), None);
        assert_eq!(BiomassGroup::of(""), None);
    }

    #[test]
    fn storage_rises_with_diameter_and_is_zero_without_a_trunk() {
        let g = BiomassGroup::Pine;
        assert!(co2_stored_kg(g, 20.0) < co2_stored_kg(g, 21.0));
        assert_eq!(co2_stored_kg(g, 0.0), 0.0);
        assert_eq!(co2_stored_kg(g, f64::NAN), 0.0);
    }
}
