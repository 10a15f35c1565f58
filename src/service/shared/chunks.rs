//! A job cut into chunks of consecutive epochs, and its result put together again from
//! its chunks' results, in epoch order. Pure functions: the queue stores what they make.

use crate::scene::{Response, Scene};

/// Estimated seconds of one triangle at one epoch on a core (the box-wing and the
/// rocket body run at 1–2e-7 s on one core of this project's machines; docs/performance.md).
const SECONDS_PER_TRIANGLE_EPOCH: f64 = 1.5e-7;

/// Estimated seconds of one pixel sample (the `image` method) on a core.
const SECONDS_PER_PIXEL_SAMPLE: f64 = 5e-8;

/// Seconds of computation a chunk aims at (on one core: the queue's overhead a chunk, a
/// claim and a write of a few ms, is then well under 1 % of it on a few cores).
pub const TARGET_CHUNK_SECONDS: f64 = 1.0;

/// Most epochs in a chunk, whatever the estimate (a chunk's result is one row).
pub const MAX_CHUNK_EPOCHS: usize = 50_000;

/// Epochs per chunk for `scene`: `fixed` when given, else about
/// [`TARGET_CHUNK_SECONDS`] of estimated work. A request with thumbnails is one chunk:
/// one exposure serves its whole sequence of images.
pub fn chunk_epochs(scene: &Scene, fixed: Option<usize>) -> usize {
    let n = scene.epochs.len().max(1);
    if scene.thumbnails.is_some() {
        return n;
    }
    if let Some(f) = fixed {
        return f.clamp(1, n);
    }
    // an articulated scene's epochs each prepare a pose ([`Scene::epoch_work`])
    let per_epoch =
        scene.mesh.triangles.len() as f64 * SECONDS_PER_TRIANGLE_EPOCH * scene.epoch_work()
            + if scene.method == crate::scene::Method::Image {
                (scene.image_size as f64 * scene.image_samples as f64).powi(2)
                    * SECONDS_PER_PIXEL_SAMPLE
            } else {
                0.0
            };
    let epochs = (TARGET_CHUNK_SECONDS / per_epoch.max(1e-9)).floor() as usize;
    epochs.clamp(1, MAX_CHUNK_EPOCHS).min(n)
}

/// The chunks of `total` epochs at `per_chunk` a chunk: (first epoch, epochs), in order.
pub fn plan(total: usize, per_chunk: usize) -> Vec<(usize, usize)> {
    let per_chunk = per_chunk.max(1);
    (0..total.max(1))
        .step_by(per_chunk)
        .map(|first| (first, per_chunk.min(total.saturating_sub(first))))
        .collect()
}

/// The part of `scene` a chunk computes: its epochs (and the site's view of them), the
/// rest as it is.
pub fn sub_scene(scene: &Scene, first: usize, epochs: usize) -> Scene {
    let end = (first + epochs).min(scene.epochs.len());
    let first = first.min(end);
    let sky = if scene.sky.len() == scene.epochs.len() {
        scene.sky[first..end].to_vec()
    } else {
        Vec::new()
    };
    Scene {
        epochs: scene.epochs[first..end].to_vec(),
        sky,
        ..scene.clone()
    }
}

/// The job's response from its chunks' responses in epoch order: the epochs joined; the
/// summary the first chunk's (method, faces, materials), with the epochs, rays and
/// computation time of all; the first chunk's thumbnails (a job with thumbnails is one
/// chunk) and warnings.
pub fn assemble(parts: Vec<Response>) -> Option<Response> {
    let mut parts = parts.into_iter();
    let mut whole = parts.next()?;
    for p in parts {
        whole.summary.rays += p.summary.rays;
        whole.summary.elapsed_ms += p.summary.elapsed_ms;
        whole.epochs.extend(p.epochs);
    }
    whole.summary.epochs = whole.epochs.len();
    Some(whole)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(epochs: usize) -> Scene {
        let mut req = crate::service::routes::example_request();
        let all = req["epochs"].as_array().unwrap().clone();
        req["epochs"] = all.iter().cycle().take(epochs).cloned().collect();
        Scene::from_json(&req.to_string(), &crate::scene::Limits::unlimited()).unwrap()
    }

    #[test]
    fn a_plan_covers_every_epoch_once_in_order() {
        assert_eq!(plan(10, 4), vec![(0, 4), (4, 4), (8, 2)]);
        assert_eq!(plan(8, 4), vec![(0, 4), (4, 4)]);
        assert_eq!(plan(3, 100), vec![(0, 3)]);
        let p = plan(10_000, 333);
        assert_eq!(p.iter().map(|c| c.1).sum::<usize>(), 10_000);
        assert!(p.windows(2).all(|w| w[0].0 + w[0].1 == w[1].0));
    }

    #[test]
    fn the_chunk_size_follows_the_work_and_a_fixed_size_wins() {
        let s = scene(5000);
        let auto = chunk_epochs(&s, None);
        assert!((1..=5000).contains(&auto));
        // a mesh ten times larger gets chunks about ten times shorter
        let mut big = s.clone();
        let tris = big.mesh.triangles.clone();
        for _ in 0..9 {
            big.mesh.triangles.extend(tris.iter().cloned());
            big.mesh
                .material_ids
                .extend(s.mesh.material_ids.iter().cloned());
        }
        let smaller = chunk_epochs(&big, None);
        assert!(
            smaller < auto || auto == 5000 && smaller <= auto,
            "{smaller} {auto}"
        );
        assert_eq!(chunk_epochs(&s, Some(250)), 250);
        assert_eq!(chunk_epochs(&s, Some(99_999)), 5000);
    }

    #[test]
    fn chunks_computed_apart_join_to_the_whole_light_curve_bit_for_bit() {
        let s = scene(23);
        let whole = crate::simulate(&s);
        let parts: Vec<Response> = plan(23, 5)
            .into_iter()
            .map(|(first, n)| crate::simulate(&sub_scene(&s, first, n)))
            .collect();
        let joined = assemble(parts).unwrap();
        assert_eq!(
            serde_json::to_string(&joined.epochs).unwrap(),
            serde_json::to_string(&whole.epochs).unwrap()
        );
        assert_eq!(joined.summary.epochs, 23);
        assert_eq!(joined.summary.rays, whole.summary.rays);
        assert_eq!(joined.summary.method, whole.summary.method);
        assert_eq!(
            crate::report::csv::to_csv(&joined),
            crate::report::csv::to_csv(&whole)
        );
    }
}
