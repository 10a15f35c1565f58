//! Named materials: the paper's two validation materials (§5.1), usable wherever a
//! material object is.

use crate::brdf::{Brdf, SeedMicrofacet};

/// A preset's name, description and BRDF.
pub struct Preset {
    pub name: &'static str,
    pub description: &'static str,
    pub brdf: fn() -> Brdf,
}

/// The presets. The paper prints "C_r" where the slope δ is meant (docs/physics.md §6.2).
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "seed-body-wrap",
        description: "satellite body wrap: kd 0.1, km 0.5, slope_rms 0.01, n 0.18 + 3.60i",
        brdf: || Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.5, 0.01, 0.18, 3.60)),
    },
    Preset {
        name: "seed-white-paint",
        description: "antenna white paint: kd 0.1, km 0.2, slope_rms 0.007, n 0.20 + 2.50i",
        brdf: || Brdf::SeedMicrofacet(SeedMicrofacet::new(0.1, 0.2, 0.007, 0.20, 2.50)),
    },
];

/// The preset called `name`.
pub fn find(name: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.name == name)
}

/// Names of all presets, for error messages.
pub fn names() -> String {
    PRESETS
        .iter()
        .map(|p| p.name)
        .collect::<Vec<_>>()
        .join(", ")
}
