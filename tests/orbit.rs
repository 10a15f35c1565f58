//! Orbits, sites, the Sun and eclipses against references the code did not produce:
//! python-sgp4 2.27 (Vallado's C++), skyfield 1.55 and ERFA's epv00, checked in as
//! `tests/fixtures/orbit/reference.json` by `tests/fixtures/orbit/make_fixtures.py`.
//! Each test prints its worst difference (`cargo test --test orbit -- --nocapture`).

use glam::DVec3;
use glint::orbit::frames::{teme_to_itrf, EarthOrientation};
use glint::orbit::pass::{self, hidden_fraction};
use glint::orbit::site::Site;
use glint::orbit::sun;
use glint::orbit::time::parse_utc;
use glint::orbit::tle::ElementSet;
use glint::orbit::UtcTime;
use serde_json::Value;
use std::collections::HashMap;

const ARCSEC_DEG: f64 = 1.0 / 3600.0;

fn reference() -> Value {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/orbit/reference.json"
    ))
    .expect("fixture");
    serde_json::from_str(&text).expect("fixture JSON")
}

fn sets(r: &Value) -> HashMap<String, ElementSet> {
    r["tles"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| {
            let lines: Vec<String> = serde_json::from_value(v.clone()).unwrap();
            (k.clone(), ElementSet::from_tle(&lines).expect("valid TLE"))
        })
        .collect()
}

fn vec3(v: &Value) -> DVec3 {
    DVec3::new(
        v[0].as_f64().unwrap(),
        v[1].as_f64().unwrap(),
        v[2].as_f64().unwrap(),
    )
}

fn site(r: &Value, name: &str) -> Site {
    let s = &r["sites"][name];
    Site {
        lat_deg: s["lat_deg"].as_f64().unwrap(),
        lon_deg: s["lon_deg"].as_f64().unwrap(),
        alt_m: s["alt_m"].as_f64().unwrap(),
    }
}

fn utc(v: &Value) -> UtcTime {
    parse_utc(v.as_str().unwrap()).expect("ISO time")
}

/// SGP4 in TEME against python-sgp4 in AFSPC mode at the same minutes since the epoch,
/// LEO, Molniya (deep space, resonant), GEO (deep space, Lyddane) and a sun-synchronous
/// LEO, from −1 to +3 days. Tolerance 1 mm (the issue's): two implementations of the same
/// equations in f64 part at ~1e-9 km per day of propagation.
#[test]
fn teme_matches_python_sgp4() {
    let r = reference();
    let sets = sets(&r);
    let (mut worst_r, mut worst_v) = (0.0f64, 0.0f64);
    for e in r["teme"].as_array().unwrap() {
        let set = &sets[e["tle"].as_str().unwrap()];
        let (p, v) = set
            .teme_at_minutes(e["tsince_min"].as_f64().unwrap())
            .unwrap();
        let dr = (p - vec3(&e["r_km"]) * 1e3).length();
        let dv = (v - vec3(&e["v_km_s"]) * 1e3).length();
        worst_r = worst_r.max(dr);
        worst_v = worst_v.max(dv);
        assert!(dr < 1e-3, "{}: {dr} m at {}", e["tle"], e["tsince_min"]);
        assert!(dv < 1e-6, "{}: {dv} m/s", e["tle"]);
    }
    println!("TEME: worst position {worst_r:.3e} m, velocity {worst_v:.3e} m/s");
}

/// A CCSDS OMM with the ISS element set's numbers propagates as its TLE does (1 mm:
/// the same elements through the same code; only the epoch's parse differs).
#[test]
fn omm_matches_its_tle() {
    let r = reference();
    let sets = sets(&r);
    let omm = serde_json::json!({
        "OBJECT_NAME": "ISS (ZARYA)", "OBJECT_ID": "1998-067A", "EPOCH": "2026-12-02T12:00:00",
        "MEAN_MOTION": 15.5, "ECCENTRICITY": 0.0005, "INCLINATION": 51.64,
        "RA_OF_ASC_NODE": 200.0, "ARG_OF_PERICENTER": 90.0, "MEAN_ANOMALY": 270.0,
        "EPHEMERIS_TYPE": 0, "CLASSIFICATION_TYPE": "U", "NORAD_CAT_ID": 25544,
        "ELEMENT_SET_NO": 999, "REV_AT_EPOCH": 4999, "BSTAR": 0.30306e-3,
        "MEAN_MOTION_DOT": 0.00016717, "MEAN_MOTION_DDOT": 0
    });
    let from_omm = ElementSet::from_omm_json(&omm).expect("OMM");
    let t = parse_utc("2026-12-03T01:00:00Z").unwrap();
    let (a, _) = from_omm.teme_at(t).unwrap();
    let (b, _) = sets["leo-iss"].teme_at(t).unwrap();
    assert!((a - b).length() < 1e-3, "{}", (a - b).length());
}

/// Azimuth, elevation and range from four WGS-84 sites against skyfield's own path
/// (TEME → GCRS → the site's horizon), UT1 = UTC and no polar motion on both sides.
/// Tolerances (the issue's): range 1 m, elevation 1″, azimuth 1″ on the sky (Δaz·cos el);
/// the object's and the site's ITRF positions 1 mm (the same IAU-82 GMST and WGS-84
/// formulae as skyfield's TEME_to_ITRF and wgs84).
#[test]
fn topocentric_matches_skyfield() {
    let r = reference();
    let sets = sets(&r);
    let eop = EarthOrientation::default();
    let (mut w_range, mut w_el, mut w_az, mut w_itrf, mut w_site) = (0f64, 0f64, 0f64, 0f64, 0f64);
    for e in r["topocentric"].as_array().unwrap() {
        let set = &sets[e["tle"].as_str().unwrap()];
        let s = site(&r, e["site"].as_str().unwrap());
        let t = utc(&e["utc"]);
        let at = pass::at(set, &s, &eop, t).unwrap();
        let d_range = (at.range_m - e["range_m"].as_f64().unwrap()).abs();
        let d_el = (at.elevation_deg - e["elevation_deg"].as_f64().unwrap()).abs();
        let mut d_az = (at.azimuth_deg - e["azimuth_deg"].as_f64().unwrap()).abs();
        d_az = d_az.min(360.0 - d_az) * at.elevation_deg.to_radians().cos();
        let d_itrf = (at.r_itrf - vec3(&e["itrf_m"])).length();
        let d_site = (s.itrf() - vec3(&e["site_itrf_m"])).length();
        w_range = w_range.max(d_range);
        w_el = w_el.max(d_el);
        w_az = w_az.max(d_az);
        w_itrf = w_itrf.max(d_itrf);
        w_site = w_site.max(d_site);
        let what = format!("{} from {} at {}", e["tle"], e["site"], e["utc"]);
        assert!(d_range < 1.0, "{what}: range {d_range} m");
        assert!(d_el < ARCSEC_DEG, "{what}: elevation {}″", d_el * 3600.0);
        assert!(d_az < ARCSEC_DEG, "{what}: azimuth {}″", d_az * 3600.0);
        assert!(d_itrf < 1e-3, "{what}: ITRF {d_itrf} m");
        assert!(d_site < 1e-3, "{what}: site {d_site} m");
    }
    println!(
        "topocentric: worst range {w_range:.3e} m, elevation {:.3e}″, azimuth {:.3e}″ \
         (on the sky), object ITRF {w_itrf:.3e} m, site ITRF {w_site:.3e} m",
        w_el * 3600.0,
        w_az * 3600.0
    );
}

/// Earth orientation given (UT1 − UTC 0.2 s, x_p 0.15″, y_p 0.35″): the ITRF position
/// against skyfield's TEME_to_ITRF with the same values, 1 mm.
#[test]
fn itrf_with_earth_orientation() {
    let r = reference();
    let sets = sets(&r);
    let mut worst = 0f64;
    for e in r["itrf_eop"].as_array().unwrap() {
        let eop = EarthOrientation {
            dut1_s: e["dut1_s"].as_f64().unwrap(),
            xp_arcsec: e["xp_arcsec"].as_f64().unwrap(),
            yp_arcsec: e["yp_arcsec"].as_f64().unwrap(),
        };
        let t = utc(&e["utc"]);
        let (p, _) = sets[e["tle"].as_str().unwrap()].teme_at(t).unwrap();
        let d = (teme_to_itrf(t, &eop) * p - vec3(&e["itrf_m"])).length();
        worst = worst.max(d);
        assert!(d < 1e-3, "{}: {d} m", e["tle"]);
    }
    println!("ITRF with EOP: worst {worst:.3e} m");
}

/// Meeus' low-accuracy Sun against ERFA's epv00 (VSOP2000-based, ~0.006″), 2025–2028,
/// in TEME, with the annual aberration the series includes. Tolerance: the series'
/// stated 0.01°. Its distance to 1e-4 AU (Meeus' R from the Keplerian ellipse errs by
/// a few 1e-5 AU).
#[test]
fn sun_within_the_series_stated_error() {
    let r = reference();
    let (mut worst_deg, mut worst_au) = (0f64, 0f64);
    for e in r["sun"].as_array().unwrap() {
        let (u, d) = sun::position(utc(&e["utc"]));
        let angle = u.angle_between(vec3(&e["apparent_unit_teme"])).to_degrees();
        let dau = (d / glint::radiometry::AU_M - e["distance_au"].as_f64().unwrap()).abs();
        worst_deg = worst_deg.max(angle);
        worst_au = worst_au.max(dau);
        assert!(angle < sun::STATED_ERROR_DEG, "{}: {angle}°", e["utc"]);
        assert!(dau < 1e-4, "{}: {dau} AU", e["utc"]);
    }
    // the Sun's elevation at the sites, through the same frames (the series' error again)
    let sets = sets(&r);
    let mut worst_el = 0f64;
    for e in r["topocentric"].as_array().unwrap() {
        let s = site(&r, e["site"].as_str().unwrap());
        let at = pass::at(
            &sets[e["tle"].as_str().unwrap()],
            &s,
            &EarthOrientation::default(),
            utc(&e["utc"]),
        )
        .unwrap();
        let d = (at.sun_elevation_deg - e["sun_elevation_deg"].as_f64().unwrap()).abs();
        worst_el = worst_el.max(d);
        assert!(d < sun::STATED_ERROR_DEG, "{}: {d}°", e["utc"]);
    }
    println!(
        "Sun: worst direction {:.2}″, distance {worst_au:.2e} AU, elevation at the sites {:.2}″",
        worst_deg * 3600.0,
        worst_el * 3600.0
    );
}

/// Eclipse contacts (first and last contact of the Earth's disk with the Sun's, and the
/// umbra's) over a day, against the same geometric shadow on python-sgp4's positions and
/// ERFA's Sun. Tolerance 1 s (the issue's); the Sun series' 0.01° moves a LEO contact by
/// ~0.15 s / sin(crossing angle). The same number of contacts is found (none are missed,
/// none invented: Molniya and GEO have none this day).
#[test]
fn eclipse_contacts_within_one_second() {
    let r = reference();
    let sets = sets(&r);
    let umbra_margin = |f: f64, umbra: bool| if umbra { f >= 1.0 } else { f > 0.0 };
    let inside = |set: &ElementSet, t: UtcTime, umbra: bool| {
        let (p, _) = set.teme_at(t).unwrap();
        let (u, d) = sun::position(t);
        umbra_margin(hidden_fraction(p, u * d), umbra)
    };
    let mut worst = 0f64;
    for w in r["eclipse_windows"].as_array().unwrap() {
        let name = w["tle"].as_str().unwrap();
        let set = &sets[name];
        let start = UtcTime::new(w["start_unix_s"].as_f64().unwrap() as i64, 0.0);
        for (kind, umbra) in [("penumbra", false), ("umbra", true)] {
            let expected: Vec<f64> = r["eclipses"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|e| e["tle"] == name && e["kind"] == kind)
                .map(|e| e["unix_s"].as_f64().unwrap())
                .collect();
            // every contact on a 20 s scan, refined by bisection to 1 ms
            let mut found = Vec::new();
            let mut prev = inside(set, start, umbra);
            for k in 1..=(86_400 / 20) {
                let t = start.plus(k as f64 * 20.0);
                let cur = inside(set, t, umbra);
                if cur != prev {
                    let (mut lo, mut hi) = (t.plus(-20.0), t);
                    while hi.seconds_since(lo) > 1e-3 {
                        let mid = lo.plus(0.5 * hi.seconds_since(lo));
                        if inside(set, mid, umbra) == prev {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    found.push(lo.unix());
                }
                prev = cur;
            }
            assert_eq!(
                found.len(),
                expected.len(),
                "{name} {kind}: {found:?} vs {expected:?}"
            );
            for (a, b) in found.iter().zip(&expected) {
                worst = worst.max((a - b).abs());
                assert!((a - b).abs() < 1.0, "{name} {kind}: {a} vs {b}");
            }
        }
    }
    println!("eclipse contacts: worst {worst:.3} s");
}
