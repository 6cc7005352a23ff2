//! `catena`: 2D finite-element dynamics of steel catenary risers and pipelines on a hysteretic seabed.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use catena_cli::commands;

use clap::{Parser, Subcommand};

/// catena: riser and pipeline dynamics on a Randolph–Quiggin seabed (SI units throughout).
#[derive(Debug, Parser)]
#[command(name = "catena", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Soil element test: the seabed law alone on one pipe segment, under displacement or load
    /// control. Writes RESULT.csv and, unless --no-plot, a PNG plot beside it.
    SoilTest {
        /// The case file (TOML with [seabed] and [test] tables).
        case: PathBuf,
        /// The CSV file to write.
        #[arg(long)]
        out: PathBuf,
        /// The PNG plot to write (default: RESULT.png beside the CSV).
        #[arg(long)]
        plot: Option<PathBuf>,
        /// Do not draw the plot.
        #[arg(long, conflicts_with = "plot")]
        no_plot: bool,
    },
    /// Fits the Randolph–Quiggin law's parameters (a chosen subset; the rest as in the start table)
    /// to an element test: a CSV with columns z (m) and P (N/m), optional leg (as `catena
    /// soil-test` writes). Writes the fitted [seabed] table to OUT (its misfit and each parameter's
    /// determination in comments), OUT's .json report and .png plot beside it.
    Calibrate {
        /// The test CSV.
        test: PathBuf,
        /// The law (randolph-quiggin).
        #[arg(long, default_value = "randolph-quiggin")]
        law: String,
        /// A TOML file with the start [seabed] table (diameter, every parameter).
        #[arg(long)]
        start: PathBuf,
        /// The keys to fit, comma-separated (su0, su_gradient, a, b, k_max, f_suc, lambda_suc,
        /// lambda_rep).
        #[arg(long)]
        fit: String,
        /// The fitted table to write (TOML).
        #[arg(long)]
        out: PathBuf,
    },
    /// Statics, then dynamics with top-end motion. Writes DIR/results.h5 (/static and /dynamic),
    /// DIR/summary.json and plots (static.png, dynamic.png, ranges.png, gauges.png with gauges, sea.png with waves).
    Run {
        /// The scene file (TOML) with a [dynamic] table.
        case: PathBuf,
        /// The output directory.
        #[arg(long)]
        out: PathBuf,
        /// Do not show a progress bar.
        #[arg(long)]
        quiet: bool,
        /// Write DIR/checkpoint.json every N time steps (replacing the previous one).
        #[arg(long, value_name = "N")]
        checkpoint_every: Option<u64>,
        /// Continue from a checkpoint written by an earlier run of the same scene.
        #[arg(long, value_name = "FILE")]
        restart: Option<PathBuf>,
        /// Compress results.h5's float fields (shuffle + deflate, on the writer thread): "yes",
        /// "no", or "auto" (when the records are decimated, output_interval > time_step, and the
        /// run has 3 threads or more: recording every step, or with fewer threads, compression
        /// would slow the run).
        #[arg(long, value_name = "WHEN", default_value = "auto", value_parser = ["auto", "yes", "no"])]
        compress: String,
        /// The threads the run may keep busy (default: the machine's cores). The line may be
        /// stepped on two threads where two are left beside the HDF5 writer's (counted when it
        /// compresses or records every step; a pipe-lay's window from 2), step by step where two
        /// are measured to be faster than one (not on cores busy with other work); the fatigue
        /// damage is counted on a thread of its own where one is left.
        /// The results are the same whatever the number; the plots have threads of their own.
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..=1024))]
        threads: Option<u64>,
    },
    /// What accuracy costs in time: the scene re-run with its element lengths and its time step
    /// scaled (by default x2, x1, x1/2, x1/4 each). Reports the key outputs with their errors
    /// (Richardson) and each run's wall time; writes DIR/convergence.csv, .json and .png.
    Convergence {
        /// The scene file (TOML) with a [dynamic] table.
        case: PathBuf,
        /// The output directory.
        #[arg(long)]
        out: PathBuf,
        /// Element-length factors, comma-separated.
        #[arg(long, value_delimiter = ',', default_values_t = [2.0, 1.0, 0.5, 0.25])]
        mesh_factors: Vec<f64>,
        /// Time-step factors, comma-separated.
        #[arg(long, value_delimiter = ',', default_values_t = [2.0, 1.0, 0.5, 0.25])]
        dt_factors: Vec<f64>,
        /// Runs at once (default 1, so that the wall times are honest).
        #[arg(long, default_value_t = 1)]
        jobs: usize,
        /// Do not print a line per run.
        #[arg(long)]
        quiet: bool,
    },
    /// Fatigue study: the scene run once per storm of a storm table (in parallel over storms), the
    /// annual damage and the life along the arc. Writes DIR/fatigue.h5, life.csv, summary.json,
    /// life.png, storms.png, and DIR/storms/<id>.json per storm (a rerun skips those done).
    Fatigue {
        /// The study file (TOML with [study] and [fatigue]).
        study: PathBuf,
        /// The output directory.
        #[arg(long)]
        out: PathBuf,
        /// Storms run at once.
        #[arg(long, default_value_t = 1)]
        jobs: usize,
        /// Do not print a line per storm.
        #[arg(long)]
        quiet: bool,
    },
    /// Strength study: a base scene with a [design_check] run for each design storm of a storm table
    /// and each of its seeds; per storm, the largest utilisation along the line over the seeds and
    /// the extremes across the seeds (Gumbel). Writes DIR/runs/<storm>-<seed>.json (a rerun skips
    /// the runs done), DIR/summary.json, utilisation.csv and strength.png.
    Strength {
        /// The study file (TOML with [study]; optional [design_check] and [extremes]).
        study: PathBuf,
        /// The output directory.
        #[arg(long)]
        out: PathBuf,
        /// Runs at once.
        #[arg(long, default_value_t = 1)]
        jobs: usize,
        /// Do not print a line per run.
        #[arg(long)]
        quiet: bool,
    },
    /// Storms in sequence: each storm of a list (or a random order by probability) run from the
    /// state the last one left, the line brought to rest between them (the seabed's memory: its
    /// trench, its degraded strength); beside it the same storms each from the as-laid state.
    /// Writes DIR/visits/, DIR/as-laid/ (a rerun resumes after the last finished visit),
    /// summary.json, trench.csv, life.csv and sequence.png.
    Sequence {
        /// The sequence file (TOML with [sequence] and [fatigue]).
        sequence: PathBuf,
        /// The output directory.
        #[arg(long)]
        out: PathBuf,
        /// Threads: the sequence takes one, the as-laid runs the others (at least 2 to run them
        /// alongside).
        #[arg(long, default_value_t = 2)]
        jobs: usize,
        /// Do not print a line per visit.
        #[arg(long)]
        quiet: bool,
    },
    /// Parameter sweep: a plan's key paths varied over a base scene or fatigue study, expanded into
    /// a sorted list of runs (point × storm); each run writes DIR/runs/<id>.json (a rerun skips the
    /// runs done), then DIR/sweep.csv and sweep.json merge them. On a cluster, --shard i --shards
    /// N (or SLURM_ARRAY_TASK_ID / SLURM_ARRAY_TASK_COUNT) runs every N-th run; --merge afterwards.
    Sweep {
        /// The plan file (TOML with [sweep]).
        plan: PathBuf,
        /// The output directory.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Print the runs, one per line, and stop.
        #[arg(long)]
        list: bool,
        /// Only merge the results already written.
        #[arg(long)]
        merge: bool,
        /// Runs at once.
        #[arg(long, default_value_t = 1)]
        jobs: usize,
        /// This shard's index, 0 ≤ i < shards.
        #[arg(long)]
        shard: Option<usize>,
        /// The number of shards.
        #[arg(long)]
        shards: Option<usize>,
        /// Do not print a line per run.
        #[arg(long)]
        quiet: bool,
    },
    /// Rainflow counting (ASTM E1049-85) of a series in a CSV file: writes CYCLES.csv with rows
    /// range,mean,count in the order found; with --sn, prints Miner's damage of the series.
    Rainflow {
        /// The CSV file: a header line, then one value per row (or several columns, with --column).
        series: PathBuf,
        /// The cycles file to write.
        #[arg(long)]
        out: PathBuf,
        /// The column to count, by its header name.
        #[arg(long)]
        column: Option<String>,
        /// An S-N curve (the series in MPa): dnv-{d,e,f1}-{air,seawater-cp,free-corrosion}.
        #[arg(long)]
        sn: Option<String>,
        /// Stress concentration factor applied to every range.
        #[arg(long, default_value_t = 1.0)]
        scf: f64,
    },
    /// Short-term extremes of recorded channels: the sample extreme, the Rayleigh, Weibull (of the
    /// up-crossing peaks) and Gumbel (of block maxima) most probable extremes and a quantile for a
    /// target duration. Writes DIR/extremes.json and DIR/extremes.png.
    Extremes {
        /// A results file (results.h5 of `catena run`) or a CSV file (`time` first, then channels).
        input: PathBuf,
        /// The output directory.
        #[arg(long)]
        out: PathBuf,
        /// A channel (repeatable): top_tension, least_tension, sag_moment, utilisation,
        /// utilisation_at_critical, moment_at_critical, gauge:NAME[:max] from a results file; a
        /// column's name from a CSV file.
        #[arg(long = "channel")]
        channels: Vec<String>,
        /// Analyse from this time, s (default: the first record).
        #[arg(long)]
        start: Option<f64>,
        /// Target duration, s.
        #[arg(long, default_value_t = 10800.0)]
        target: f64,
        /// Non-exceedance probability of the reported quantile.
        #[arg(long, default_value_t = 0.9)]
        quantile: f64,
        /// Block length for the Gumbel fit of block maxima, s.
        #[arg(long, default_value_t = 600.0)]
        block: f64,
    },
    /// An animated GIF of the touchdown zone from a run's results.h5: the whole line, the touchdown
    /// zone to a true vertical scale with the seabed and the trench as it forms (nodes coloured by
    /// penetration or seabed force), the bending moment along the arc, time and top motion.
    Animate {
        /// The results file (results.h5 of `catena run`).
        results: PathBuf,
        /// The GIF to write.
        #[arg(long)]
        out: PathBuf,
        /// The most frames, chosen evenly from the records.
        #[arg(long, default_value_t = 120)]
        frames: usize,
        /// Frames a second.
        #[arg(long, default_value_t = 12.0)]
        fps: f64,
        /// What colours the nodes: penetration (m) or seabed-force (N/m).
        #[arg(long, default_value = "penetration")]
        colour: String,
    },
    /// Reads and checks a scene, a fatigue study, a sweep plan or a soil test without running it:
    /// prints what would run (the effects built, elements, steps, estimated time, memory and disk)
    /// and every warning. Exits with 2 and the error if the file is wrong.
    Check {
        /// The file (TOML).
        case: PathBuf,
    },
    /// Static configuration of a riser or pipeline on the seabed (initial-penetration mode only).
    /// Writes DIR/results.h5, DIR/summary.json and DIR/static.png.
    Static {
        /// The scene file (TOML).
        case: PathBuf,
        /// The output directory.
        #[arg(long)]
        out: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match dispatch(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Runs one command, its text printed on standard output.
fn dispatch(command: Command) -> Result<(), catena::AppError> {
    match command {
        Command::Calibrate {
            test,
            law,
            start,
            fit,
            out,
        } => catena_cli::calibrate::run(&test, &law, &start, &fit, &out).map(|t| print!("{t}")),
        Command::SoilTest {
            case,
            out,
            plot,
            no_plot,
        } => {
            let plot = if no_plot {
                None
            } else {
                Some(plot.unwrap_or_else(|| out.with_extension("png")))
            };
            commands::soil_test(&case, &out, plot.as_deref()).map(|t| print!("{t}"))
        }
        Command::Run {
            case,
            out,
            quiet,
            checkpoint_every,
            restart,
            compress,
            threads,
        } => {
            let stop = Some(stop_on_signal());
            commands::run(
                &case,
                &out,
                &commands::RunCommandOptions {
                    progress: !quiet,
                    checkpoint_every,
                    restart,
                    stop,
                    stop_after: None,
                    compress: match compress.as_str() {
                        "yes" => Some(true),
                        "no" => Some(false),
                        _ => None,
                    },
                    threads: threads.and_then(|t| usize::try_from(t).ok()),
                },
            )
            .map(|t| print!("{t}"))
        }
        Command::Convergence {
            case,
            out,
            mesh_factors,
            dt_factors,
            jobs,
            quiet,
        } => commands::convergence(
            &case,
            &out,
            &catena::studies::convergence::ConvergenceOptions {
                mesh_factors,
                dt_factors,
                jobs,
                progress: !quiet,
            },
        )
        .map(|t| print!("{t}")),
        Command::Fatigue {
            study,
            out,
            jobs,
            quiet,
        } => commands::fatigue(&study, &out, jobs, !quiet).map(|t| print!("{t}")),
        Command::Strength {
            study,
            out,
            jobs,
            quiet,
        } => commands::strength(&study, &out, jobs, !quiet).map(|t| print!("{t}")),
        Command::Sequence {
            sequence,
            out,
            jobs,
            quiet,
        } => catena_cli::sequence::run(&sequence, &out, jobs, !quiet).map(|t| print!("{t}")),
        Command::Sweep {
            plan,
            out,
            list,
            merge,
            jobs,
            shard,
            shards,
            quiet,
        } => commands::sweep(
            &plan,
            &commands::SweepOptions {
                out,
                list,
                merge_only: merge,
                jobs,
                shard,
                shards,
                progress: !quiet,
            },
        )
        .map(|t| print!("{t}")),
        Command::Rainflow {
            series,
            out,
            column,
            sn,
            scf,
        } => commands::rainflow(&series, &out, column.as_deref(), sn.as_deref(), scf)
            .map(|t| print!("{t}")),
        Command::Animate {
            results,
            out,
            frames,
            fps,
            colour,
        } => commands::animate(&results, &out, frames, fps, &colour).map(|t| print!("{t}")),
        Command::Extremes {
            input,
            out,
            channels,
            start,
            target,
            quantile,
            block,
        } => commands::extremes(
            &input,
            &out,
            &commands::ExtremesOptions {
                channels,
                start,
                settings: catena::checks::extremes::Settings {
                    target,
                    quantile,
                    block,
                },
            },
        )
        .map(|t| print!("{t}")),
        Command::Check { case } => commands::check(&case).map(|t| print!("{t}")),
        Command::Static { case, out } => commands::static_(&case, &out).map(|t| print!("{t}")),
    }
}

/// SIGINT and SIGTERM end a run at its next converged step; its records are flushed and
/// summary.json says where it stopped.
fn stop_on_signal() -> Arc<AtomicBool> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    if let Err(e) = ctrlc::set_handler(move || flag.store(true, Ordering::SeqCst)) {
        eprintln!("warning: cannot catch SIGINT/SIGTERM ({e}); an interrupted run keeps its records up to the last flush");
    }
    stop
}
