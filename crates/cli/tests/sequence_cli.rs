//! `catena sequence`: three short visits in sequence on the degrading Randolph–Quiggin seabed of
//! `cases/scr1000/memory/`, through the command: the first visit is the as-laid one to the bit, the
//! later ones start from the trench the earlier dug (deeper than the as-laid penetration, different
//! damage), degradation leaves the touchdown zone weaker and regain at rest gives strength back, a
//! resumed sequence gives the same bits, and bad sequence input is named.

use std::path::{Path, PathBuf};

use catena::sequence::VisitResult;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("sequence_cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

/// A sequence of three visits (storms 23, 24, 23 of the table) of 40 s after a 40 s transient, a
/// 60 s settling, on the degrading scene; `extra` is added to `[sequence]`.
fn short_sequence(d: &Path, extra: &str) -> PathBuf {
    let memory = root().join("cases/scr1000/memory");
    let storms = root().join("cases/scr1000/fatigue/gom-30-storms.toml");
    let path = d.join("sequence.toml");
    std::fs::write(
        &path,
        format!(
            "[sequence]\nscene = \"{}\"\nstorms = \"{}\"\norder = [23, 24, 23]\nrecord = 40.0\ntransient = 40.0\n\
             settle = 60.0\n{extra}\n[fatigue]\nsn_curve = \"dnv-e-seawater-cp\"\nscf = 1.2\nfibres = [\"outer\"]\n",
            memory.join("scr1000-rq-degrading.toml").display(),
            storms.display()
        ),
    )
    .expect("sequence");
    path
}

fn visit(path: &Path) -> VisitResult {
    serde_json::from_str(&std::fs::read_to_string(path).expect("visit")).expect("json")
}

fn bits(v: &VisitResult) -> Vec<u64> {
    let mut b: Vec<u64> = v.damage[0].1.iter().map(|x| x.to_bits()).collect();
    b.extend(v.trench.iter().map(|x| x.to_bits()));
    b.extend(v.strength.iter().map(|x| x.to_bits()));
    b
}

#[test]
fn visits_carry_the_trench_and_the_soil_and_resume_to_the_bit() {
    let d = dir("three");
    let seq = short_sequence(&d, "calm = 0.0");
    let out = d.join("out");
    let text = catena_cli::sequence::run(&seq, &out, 2, false).expect("sequence");
    println!("{text}");
    let v: Vec<VisitResult> = (0..3)
        .map(|k| visit(&out.join(format!("visits/visit-{k:04}.json"))))
        .collect();
    let laid: Vec<VisitResult> = (0..3)
        .map(|k| visit(&out.join(format!("as-laid/visit-{k:04}.json"))))
        .collect();
    // The first visit starts from the statics, as the as-laid one does.
    assert_eq!(v[0].damage, laid[0].damage);
    // Later visits start from the trench: a different response, a deeper trench.
    assert_ne!(v[1].damage, laid[1].damage);
    let st: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary"))
            .expect("json");
    let deepest = |t: &[f64]| t.iter().copied().fold(0.0f64, f64::max);
    let csv = std::fs::read_to_string(out.join("trench.csv")).expect("trench");
    let as_laid = csv
        .lines()
        .skip(1)
        .map(|l| {
            l.split(',')
                .nth(1)
                .and_then(|x| x.parse::<f64>().ok())
                .unwrap_or(0.0)
        })
        .fold(0.0f64, f64::max);
    assert!(
        deepest(&v[0].trench) > 1.2 * as_laid && deepest(&v[2].trench) > deepest(&v[0].trench),
        "as laid {as_laid}, after the visits {} {}",
        deepest(&v[0].trench),
        deepest(&v[2].trench)
    );
    // Degradation: the touchdown zone is weaker than intact after the visits (no rest: calm = 0).
    let weakest = v[2].strength.iter().copied().fold(1.0f64, f64::min);
    assert!(weakest < 0.99, "least strength factor {weakest}");
    assert_eq!(st["visits_done"], 3);
    // Resume: the last visit's files removed (a sequence killed during it), the rerun gives its bits.
    let before = bits(&v[2]);
    for f in ["visits/visit-0002.json", "visits/carry-0002.json"] {
        std::fs::remove_file(out.join(f)).expect("remove");
    }
    let text = catena_cli::sequence::run(&seq, &out, 1, false).expect("resumed");
    assert!(text.contains("(2 resumed)"), "{text}");
    assert_eq!(
        bits(&visit(&out.join("visits/visit-0002.json"))),
        before,
        "the resumed visit is the uninterrupted one to the bit"
    );
    // Regain: the same visits with a long rest between them end stronger.
    let d2 = dir("rested");
    let seq2 = short_sequence(&d2, "calm = 300000.0\nas_laid = false");
    let out2 = d2.join("out");
    catena_cli::sequence::run(&seq2, &out2, 1, false).expect("sequence");
    let rested = visit(&out2.join("visits/visit-0002.json"));
    let weakest_rested = rested.strength.iter().copied().fold(1.0f64, f64::min);
    assert!(
        weakest_rested > weakest + 0.5 * (1.0 - weakest),
        "after rests of 10 t50: {weakest_rested}, without rest {weakest}"
    );
}

/// Bad sequence input: a storm not in the table, a negative calm, both an order and a random
/// table, a zero settling step, fewer random visits than storms, a missing scene, a bad S-N curve,
/// SCF or fibre in its own `[fatigue]`: each error names the sequence's file and the key.
#[test]
fn bad_sequence_input_is_named() {
    let d = dir("bad");
    for (extra, order, key) in [
        ("calm = 0.0", Some("order = [23, 99]"), "sequence.order[1]"),
        ("calm = -5.0", None, "sequence.calm"),
        (
            "calm = 0.0\n[sequence.random]\nseed = 1\nvisits = 3",
            None,
            "sequence.order",
        ),
        (
            "calm = 0.0\nsettle_time_step = 0.0",
            None,
            "sequence.settle_time_step",
        ),
        (
            "calm = 0.0\n[sequence.random]\nseed = 1\nvisits = 12",
            Some(""),
            "sequence.random.visits",
        ),
        (
            "calm = 0.0\nscene = \"missing.toml\"",
            None,
            "sequence.scene",
        ),
    ] {
        let seq = short_sequence(&d, extra);
        let mut text = std::fs::read_to_string(&seq).expect("read");
        if let Some(o) = order {
            text = text.replace("order = [23, 24, 23]", o);
        }
        if extra.contains("scene = ") {
            // The first `scene` key is the good one: drop it.
            let first = text.find("scene = ").expect("scene");
            let end = first + text[first..].find('\n').expect("line");
            text.replace_range(first..=end, "");
        }
        std::fs::write(&seq, text).expect("write");
        check(&seq, key);
    }
    // The sequence's own [fatigue] table: its errors name the sequence's file, not the scene's.
    for (from, to, key) in [
        (
            "sn_curve = \"dnv-e-seawater-cp\"",
            "sn_curve = \"dnv-z\"",
            "fatigue.sn_curve",
        ),
        ("scf = 1.2", "scf = 0.0", "fatigue.scf"),
        (
            "fibres = [\"outer\"]",
            "fibres = [\"middle\"]",
            "fatigue.fibres",
        ),
    ] {
        let seq = short_sequence(&d, "calm = 0.0");
        let text = std::fs::read_to_string(&seq)
            .expect("read")
            .replace(from, to);
        std::fs::write(&seq, text).expect("write");
        check(&seq, key);
    }
}

/// The sequence's error names the sequence's file and the key.
fn check(seq: &std::path::Path, key: &str) {
    let d = seq.parent().expect("dir");
    {
        let e = catena_cli::sequence::run(seq, &d.join("out"), 1, false)
            .expect_err("bad input")
            .to_string();
        assert!(
            e.contains(&format!("sequence.toml: key `{key}")),
            "{key}: {e}"
        );
    }
}
