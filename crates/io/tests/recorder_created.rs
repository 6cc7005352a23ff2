//! `Recorder::when_created`: the call that `catena run`'s static plot waits on returns once the
//! writer thread has created `results.h5`, long before its limit.

use std::time::{Duration, Instant};

use catena_io::h5::Recorder;

mod common;

#[test]
fn when_created_returns_once_the_writer_has_made_the_file() {
    let st = catena::statics::solve(common::heave_scene(&[])).expect("its statics");
    let dir = std::env::temp_dir().join(format!("catena-created-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch folder");
    let path = dir.join("results.h5");
    let _ = std::fs::remove_file(&path);
    let rec = Recorder::create(&path, &st, &[], false).expect("the recorder");
    let wait = rec.when_created(Duration::from_secs(3));
    let t = Instant::now();
    wait();
    assert!(
        t.elapsed() < Duration::from_secs(2),
        "waited {:?}: the writer never said it had created the file",
        t.elapsed()
    );
    let size = std::fs::metadata(&path).expect("results.h5 is there").len();
    assert!(size > 1000, "{size} bytes");
    drop(rec);
    let _ = std::fs::remove_dir_all(&dir);
}
