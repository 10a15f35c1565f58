//! The Earth across the line of sight: the object still shines (its intensity is its
//! own), but nothing reaches the observer — irradiance 0, magnitude null, the epoch
//! flagged; and an Earth off to the side changes nothing.

use glint::{Limits, Scene};
use serde_json::json;

#[test]
fn an_earth_between_object_and_observer_hides_the_object() {
    let request = json!({
        "object": {
            "mesh": {
                "vertices": [[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]],
                "triangles": [[0, 1, 2], [0, 2, 3]],
                "material_ids": [0, 0]
            },
            "materials": [ { "name": "white", "model": "lambert", "albedo": 0.5 } ]
        },
        "illumination": { "earthshine": "off" },
        "epochs": [
            // the Earth 90° from the Sun and from the observer: no eclipse, no occultation
            { "t": 0, "sun": [1, 0, 1], "observer": [0, 0, 1e8], "earth": [5e7, 0, -5e7] },
            // the Earth halfway to the observer, 45° from the Sun (it subtends 7.3°)
            { "t": 1, "sun": [1, 0, 1], "observer": [0, 0, 1e8], "earth": [0, 0, 5e7] },
            // no Earth given: nothing to check
            { "t": 2, "sun": [1, 0, 1], "observer": [0, 0, 1e8] }
        ]
    });
    let scene = Scene::from_json(&request.to_string(), &Limits::unlimited()).expect("valid");
    let r = glint::simulate(&scene);
    let (clear, hidden, none) = (&r.epochs[0], &r.epochs[1], &r.epochs[2]);
    assert!(!clear.earth_blocks_view && !none.earth_blocks_view);
    assert_eq!(clear.eclipse, 0.0);
    assert_eq!(hidden.eclipse, 0.0, "the Sun is not behind the Earth here");
    // a 1 m² Lambert plate lit and seen at 45° and 0°: E = E_sun·ρ/π·cos45°·1 m²/R²
    assert!(clear.irradiance_w_m2 > 0.0 && clear.magnitude.is_some());
    assert_eq!(clear.irradiance_w_m2, none.irradiance_w_m2);
    assert!(hidden.earth_blocks_view);
    assert_eq!(hidden.irradiance_w_m2, 0.0);
    assert_eq!(hidden.sun_w_m2, 0.0);
    assert_eq!(hidden.earthshine_w_m2, 0.0);
    assert_eq!(hidden.magnitude, None);
    assert_eq!(hidden.magnitude_1000km, None);
    assert_eq!(hidden.magnitude_standard, None);
    assert_eq!(hidden.magnitude_intrinsic, None);
    // the object's own radiant intensity is unchanged: only its path to the observer is cut
    assert_eq!(hidden.intensity_w_sr, clear.intensity_w_sr);
}
