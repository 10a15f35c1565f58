//! The service on a full disk: a small tmpfs holds the job store, a filler file takes the
//! rest of its space. Needs the right to mount (root in a container that allows it);
//! without it the test says so and passes without running.

mod service_support;

use service_support::*;
use std::path::Path;
use std::process::Command;
use std::time::Duration;

/// A tmpfs of `mib` MiB at `dir`, unmounted on drop.
struct Tmpfs(std::path::PathBuf);

impl Tmpfs {
    fn mount(dir: &Path, mib: u32) -> Option<Tmpfs> {
        std::fs::create_dir_all(dir).ok()?;
        let ok = Command::new("mount")
            .args(["-t", "tmpfs", "-o", &format!("size={mib}m"), "tmpfs"])
            .arg(dir)
            .output()
            .is_ok_and(|o| o.status.success());
        ok.then(|| Tmpfs(dir.to_path_buf()))
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg("-l").arg(&self.0).status();
    }
}

/// Writes zeros to `path` until the filesystem refuses (ENOSPC).
fn fill(path: &Path) {
    use std::io::Write;
    let mut f = std::fs::File::create(path).unwrap();
    let block = vec![0u8; 64 * 1024];
    while f.write_all(&block).is_ok() {}
    let _ = f.sync_all();
}

#[test]
fn a_full_disk_is_a_507_readyz_fails_and_the_store_recovers_without_a_restart() {
    let mnt = std::env::temp_dir().join(format!("glint-test-{}-tmpfs", std::process::id()));
    let Some(fs) = Tmpfs::mount(&mnt, 8) else {
        eprintln!("skipped: cannot mount a tmpfs here (needs root and the right to mount)");
        return;
    };
    let data = fs.0.join("data");
    let server = Server::start("disk", |c| c.data_dir = data.clone());
    assert_eq!(get(server.addr, "/readyz").status, 200);
    let filler = fs.0.join("filler");
    fill(&filler);

    // ~0.5 MB bodies: the store's file must grow for each, and cannot
    let big = scene_request_repeated("box-wing", 2_000);
    let mut full = None;
    for _ in 0..40 {
        let r = post_json(server.addr, "/v1/jobs", &big);
        if r.status != 202 {
            full = Some(r);
            break;
        }
    }
    let r = full.expect("the disk never filled");
    assert_eq!(r.status, 507, "{}", r.text());
    assert!(
        r.json()["error"].as_str().unwrap().contains("full"),
        "{}",
        r.text()
    );
    // while it cannot write, the service is not ready, but it stays alive
    assert_eq!(get(server.addr, "/readyz").status, 503);
    assert_eq!(get(server.addr, "/healthz").status, 200);

    // space returns: ready again, and submissions are stored, without a restart
    std::fs::remove_file(&filler).unwrap();
    let start = std::time::Instant::now();
    while get(server.addr, "/readyz").status != 200 {
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "never ready again"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    let r = post_json(server.addr, "/v1/jobs", &scene_request("plate", 2));
    assert_eq!(r.status, 202, "{}", r.text());
    let id = r.json()["id"].as_str().unwrap().to_string();
    let s = wait_final(server.addr, &id, &[], Duration::from_secs(60));
    assert_eq!(s["state"], "done", "{s}");

    // the database file deleted under the running service: not ready
    std::fs::remove_file(data.join("glint.redb")).unwrap();
    assert_eq!(get(server.addr, "/readyz").status, 503);
    drop(server);
}

#[test]
fn an_unwritable_data_dir_is_refused_naming_its_path() {
    let dir = temp_dir("readonly");
    let file = dir.join("not-a-dir");
    std::fs::write(&file, b"x").unwrap();
    let rt = tokio::runtime::Runtime::new().unwrap();
    let config = glint::service::Config {
        addr: "127.0.0.1:0".parse().unwrap(),
        data_dir: file.join("data"),
        ..Default::default()
    };
    let err = rt
        .block_on(glint::service::start(config))
        .err()
        .expect("refused");
    let msg = format!("{err:#}");
    assert!(msg.contains("not-a-dir"), "{msg}");
    let _ = std::fs::remove_dir_all(&dir);
}
