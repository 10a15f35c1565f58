//! The light curve as CSV: one row per epoch, the JSON fields as columns.

use crate::scene::Response;
use std::fmt::Write;

/// Column names, in order.
pub const HEADER: &str = "t,irradiance_w_m2,sun_w_m2,earthshine_w_m2,intensity_w_sr,magnitude,magnitude_1000km,magnitude_standard,magnitude_intrinsic,phase_angle_deg,range_m,lit_visible_area_m2,eclipse,earth_blocks_view";

/// Columns added after [`HEADER`] when the epochs came from a `geometry`.
pub const GEOMETRY_HEADER: &str = ",azimuth_deg,elevation_deg,sun_elevation_deg,in_earth_shadow";

/// Columns added at the end when the request had an `observation`.
pub const OBSERVATION_HEADER: &str =
    ",signal_e,sky_e,noise_e,snr,signal_adu,saturated,sample_e,sample_magnitude";

/// CSV text with a header; an absent magnitude (no light) is an empty cell. A
/// `geometry` request's curve has the site's view as four more columns.
pub fn to_csv(response: &Response) -> String {
    let mut out = Vec::with_capacity(64 + response.epochs.len() * 200);
    write_csv(response, &mut out).expect("writing to memory cannot fail");
    String::from_utf8(out).expect("the CSV is ASCII")
}

/// [`to_csv`] written row by row to `out` (a file, or the service's store), never whole
/// in memory.
pub fn write_csv(response: &Response, out: &mut impl std::io::Write) -> std::io::Result<()> {
    let sky = response.epochs.iter().any(|e| e.azimuth_deg.is_some());
    let mut s = String::with_capacity(512);
    s.push_str(HEADER);
    if sky {
        s.push_str(GEOMETRY_HEADER);
    }
    let observed = response.epochs.iter().any(|e| e.observation.is_some());
    if observed {
        s.push_str(OBSERVATION_HEADER);
    }
    s.push('\n');
    out.write_all(s.as_bytes())?;
    let opt = |m: Option<f64>| m.map(|x| format!("{x:.6}")).unwrap_or_default();
    for e in &response.epochs {
        s.clear();
        let _ = write!(
            s,
            "{},{:e},{:e},{:e},{:e},{},{},{},{},{:.6},{:.6e},{:.6e},{:.6},{}",
            e.t,
            e.irradiance_w_m2,
            e.sun_w_m2,
            e.earthshine_w_m2,
            e.intensity_w_sr,
            opt(e.magnitude),
            opt(e.magnitude_1000km),
            opt(e.magnitude_standard),
            opt(e.magnitude_intrinsic),
            e.phase_angle_deg,
            e.range_m,
            e.lit_visible_area_m2,
            e.eclipse,
            u8::from(e.earth_blocks_view)
        );
        if sky {
            let _ = write!(
                s,
                ",{},{},{},{}",
                opt(e.azimuth_deg),
                opt(e.elevation_deg),
                opt(e.sun_elevation_deg),
                e.in_earth_shadow
                    .map(|b| u8::from(b).to_string())
                    .unwrap_or_default()
            );
        }
        if observed {
            if let Some(o) = &e.observation {
                let _ = write!(
                    s,
                    ",{:e},{:e},{:e},{:.6e},{:e},{},{:e},{}",
                    o.signal_e,
                    o.sky_e,
                    o.noise_e,
                    o.snr,
                    o.signal_adu,
                    u8::from(o.saturated),
                    o.sample_e,
                    opt(o.sample_magnitude)
                );
            } else {
                s.push_str(",,,,,,,,");
            }
        }
        s.push('\n');
        out.write_all(s.as_bytes())?;
    }
    Ok(())
}
