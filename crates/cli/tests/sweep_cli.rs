//! `catena sweep`: a small plan (a two-storm study of 30 s per storm, three parameter points, one of
//! which fails) through the command: the list, the merged table against `catena fatigue` on the
//! same study, resume, the same merged table to the bit from two shards (by flags and by Slurm's
//! environment), and a failing point reported while the others go on.

use std::path::{Path, PathBuf};

use catena_cli::commands::{self, SweepOptions};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("sweep_cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}

fn plan(d: &Path) -> PathBuf {
    for f in ["scr1000-linear-k100.toml", "semi-rao.csv"] {
        std::fs::copy(root().join("cases/scr1000/fatigue").join(f), d.join(f)).expect("copy");
    }
    std::fs::write(
        d.join("storms.toml"),
        "[[storm]]\nid = 22\nhs = 5.0\ntp = 8.4\nprobability = 0.002\n\n\
         [[storm]]\nid = 23\nhs = 5.0\ntp = 9.9\nprobability = 0.004\n",
    )
    .expect("storms");
    std::fs::write(
        d.join("study.toml"),
        "[study]\nscene = \"scr1000-linear-k100.toml\"\nstorms = \"storms.toml\"\nrecord = 20.0\ntransient = 10.0\n\n\
         [fatigue]\nsn_curve = \"dnv-e-seawater-cp\"\nscf = 1.2\nfibres = [\"outer\"]\n",
    )
    .expect("study");
    let p = d.join("plan.toml");
    std::fs::write(
        &p,
        "[sweep]\nbase = \"study.toml\"\ncombine = \"product\"\n\
         [[sweep.parameter]]\nkey = \"seabed.stiffness\"\nvalues = [100e3, 1000e3, -5.0]\n",
    )
    .expect("plan");
    p
}

fn opts(out: &Path) -> SweepOptions {
    SweepOptions {
        out: Some(out.to_path_buf()),
        jobs: 2,
        ..Default::default()
    }
}

fn rows(p: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(p)
        .expect("csv")
        .lines()
        .map(|l| l.splitn(6, ',').map(String::from).collect())
        .collect()
}

#[test]
fn a_small_plan_runs_resumes_shards_and_merges() {
    let d = dir("small");
    let p = plan(&d);
    // The list: point × storm, sorted.
    let list = commands::sweep(
        &p,
        &SweepOptions {
            list: true,
            ..Default::default()
        },
    )
    .expect("list");
    let ids: Vec<&str> = list
        .lines()
        .map(|l| l.split('\t').next().expect("id"))
        .collect();
    assert_eq!(
        ids,
        [
            "p000-s022",
            "p000-s023",
            "p001-s022",
            "p001-s023",
            "p002-s022",
            "p002-s023"
        ]
    );

    let out = d.join("out");
    let text = commands::sweep(&p, &opts(&out)).expect("sweep");
    println!("{text}");
    let t = rows(&out.join("sweep.csv"));
    let local_bytes = std::fs::read(out.join("sweep.csv")).expect("local");
    assert_eq!(
        t[0],
        [
            "seabed.stiffness",
            "min_life_years",
            "min_life_arc",
            "tdz_moment_range",
            "max_penetration",
            "status"
        ]
    );
    assert_eq!(t.len(), 4);
    assert_eq!(t[1][5], "ok");
    assert_eq!(t[2][5], "ok");
    assert!(
        t[3][5].starts_with("\"failed: run p002-s022") && t[3][5].contains("seabed.stiffness"),
        "{}",
        t[3][5]
    );
    assert!(t[3][1].is_empty(), "a failed point has no life");
    // The stiffer seabed: shorter life, less penetration (the trend of the paper's Figure 9).
    let num = |s: &str| s.parse::<f64>().expect("number");
    assert!(num(&t[2][1]) < num(&t[1][1]));
    assert!(num(&t[2][4]) < num(&t[1][4]));

    // Point 0 is the study itself: its life is `catena fatigue`'s.
    let fat = d.join("fatigue");
    commands::fatigue(&d.join("study.toml"), &fat, 2, false).expect("fatigue");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(fat.join("summary.json")).expect("summary"))
            .expect("json");
    let life = s["min_life_years"].as_f64().expect("life");
    assert!(
        (num(&t[1][1]) / life - 1.0).abs() < 1e-12,
        "{} vs {life}",
        t[1][1]
    );
    assert_eq!(num(&t[1][2]), s["min_life_arc"].as_f64().expect("arc"));

    // Resume: the completed runs are taken from the first run (the failed ones are tried again).
    let again = commands::sweep(&p, &opts(&out)).expect("again");
    assert!(again.contains("6 runs (4 from an earlier run)"), "{again}");
    assert_eq!(rows(&out.join("sweep.csv")), t);

    // A plan that gains a value re-runs only the new point's runs.
    let text = std::fs::read_to_string(&p).expect("plan");
    std::fs::write(
        &p,
        text.replace("[100e3, 1000e3, -5.0]", "[100e3, 300e3, 1000e3, -5.0]"),
    )
    .expect("plan");
    let grown = commands::sweep(&p, &opts(&out)).expect("grown");
    assert!(grown.contains("8 runs (4 from an earlier run)"), "{grown}");
    std::fs::write(&p, text).expect("plan");

    // Two shards, one by flags and one by Slurm's environment, then a merge: the same table.
    let sh = d.join("shards");
    let one = SweepOptions {
        shard: Some(0),
        shards: Some(2),
        ..opts(&sh)
    };
    let first = commands::sweep(&p, &one).expect("shard 0");
    assert!(first.contains("shard 0 of 2: 3 runs"), "{first}");
    assert!(!sh.join("sweep.csv").exists(), "a shard does not merge");
    std::env::set_var("SLURM_ARRAY_TASK_ID", "1");
    std::env::set_var("SLURM_ARRAY_TASK_COUNT", "2");
    let second = commands::sweep(&p, &opts(&sh));
    std::env::remove_var("SLURM_ARRAY_TASK_ID");
    std::env::remove_var("SLURM_ARRAY_TASK_COUNT");
    assert!(second.expect("shard 1").contains("shard 1 of 2: 3 runs"));
    commands::sweep(
        &p,
        &SweepOptions {
            merge_only: true,
            ..opts(&sh)
        },
    )
    .expect("merge");
    assert!(
        std::fs::read(sh.join("sweep.csv")).expect("merged") == local_bytes,
        "merged shards differ from the local run"
    );
}

#[test]
fn bad_plans_are_named() {
    let d = dir("bad");
    let p = plan(&d);
    for (text, key) in [
        ("[sweep]\nbase = \"study.toml\"\n", "parameter"),
        ("[sweep]\nbase = \"study.toml\"\ncombine = \"cross\"\n[[sweep.parameter]]\nkey = \"seabed.stiffness\"\nvalues = [1e5]\n", "sweep.combine"),
        ("[sweep]\nbase = \"study.toml\"\ncombine = \"zip\"\n[[sweep.parameter]]\nkey = \"a\"\nvalues = [1, 2]\n[[sweep.parameter]]\nkey = \"b\"\nvalues = [1]\n", "sweep.combine"),
        ("[sweep]\nbase = \"nowhere.toml\"\n[[sweep.parameter]]\nkey = \"a\"\nvalues = [1]\n", "sweep.base"),
        ("[sweep]\nbase = \"study.toml\"\n[[sweep.parameter]]\nkey = \"a\"\nvalues = []\n", "values"),
    ] {
        std::fs::write(&p, text).expect("plan");
        let e = commands::sweep(&p, &opts(&d.join("o"))).expect_err(text).to_string();
        assert!(e.contains("plan.toml") && e.contains(key), "{e}");
    }
}
