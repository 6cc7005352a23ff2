//! Soil parameters fitted to an element test (`catena calibrate TEST.csv`): the Randolph–Quiggin
//! law's parameters, a chosen subset of them, the rest fixed at a start table's values.
//!
//! **The test** is a CSV with a header naming at least the columns `z` (penetration of the invert,
//! m, positive down) and `P` (soil resistance per unit length without soil buoyancy, N/m, positive
//! up); an optional `leg` column numbers the test's legs, each of which must be monotonic in `z`
//! (a leg is one direction of travel). `catena soil-test` writes such a file. At least
//! [`MIN_POINTS`] points.
//!
//! **The forward model** walks the law along the recorded penetrations from an untouched node, each
//! interval in equal steps of at most `D/500` (the law is step-size independent at that step, to
//! 1e-6: `docs/seabed-model.md`), committing every step, and takes the force at each recorded point.
//! Whether the test was run under displacement or load control, its recorded path is what the law
//! is driven along.
//!
//! **The misfit** is the root mean square of `P_model − P_test` over the points, reported also
//! relative to the largest `|P_test|`. It is minimised over the fitted parameters by the
//! Nelder–Mead simplex of the `argmin` crate (no derivatives: the law's branches make the misfit
//! non-smooth), in transformed coordinates that keep each parameter in its range: `ln v` for the
//! positive ones (`su0`, `su_gradient`, `a`, `k_max`, `lambda_suc`, `lambda_rep`), the logit for
//! `b` and `f_suc` (in (0, 1)). The simplex starts at the start table with a 10 % step in each
//! coordinate and is restarted once from its best point.
//!
//! **Sensitivity.** At the fit, the Jacobian `J_ik = ∂(P_model,i)/∂(ln v_k)` by central differences
//! (a step of 1e-3 in `ln v`). Reported per parameter: the sensitivity `‖J_k‖/√N` (the RMS change
//! of `P` for a unit change of `ln v`, i.e. ×100 for 1 %, relative to the largest `|P_test|`); the
//! relative standard error `√((JᵀJ)⁻¹_kk·s²)`, `s² = Σr²/(N − p)` (zero for a noiseless
//! synthetic test); the correlations; the standard error a scatter of 0.1 % of the peak force
//! would give, `10⁻³·P_peak·√((JᵀJ)⁻¹_kk)` (the test's power to determine the parameter, whatever
//! its own scatter: it grows when parameters are correlated and shrinks with more points); and a
//! verdict: *not determined* when a 1 % change moves the fit by less than 10⁻⁵ of the peak (the
//! test does not exercise it; left out of the inverse), *well determined* when that reference error
//! is below 1 %, *weakly determined* otherwise.

use argmin::core::{CostFunction, Executor, State};
use argmin::solver::neldermead::NelderMead;
use catena_seabed::{RandolphQuiggin, RqHistory, RqParams};
use serde::Serialize;

use crate::error::{AppError, SceneError};
use crate::scene::invalid;

/// The fewest points a test must have.
pub const MIN_POINTS: usize = 10;

/// The parameters that can be fitted, as the `[seabed]` keys spell them.
pub const FITTABLE: [&str; 8] = [
    "su0",
    "su_gradient",
    "a",
    "b",
    "k_max",
    "f_suc",
    "lambda_suc",
    "lambda_rep",
];

/// An element test read from a CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct TestData {
    /// Its file, for messages.
    pub file: String,
    /// Penetration at each point, m.
    pub z: Vec<f64>,
    /// Soil resistance at each point, N/m.
    pub p: Vec<f64>,
}

/// Reads a test CSV (columns `z`, `P`, optional `leg`; any others ignored). Errors name the file,
/// the column or row, and what was expected: too few points, a value that is not a finite number,
/// a leg that is not monotonic in `z`.
pub fn read_test(file: &str, text: &str) -> Result<TestData, SceneError> {
    let mut lines = text
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'));
    let header: Vec<String> = lines
        .next()
        .ok_or_else(|| invalid(file, "header", "a header line naming the columns z and P"))?
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    let col = |name: &str| header.iter().position(|h| h == name);
    let iz = col("z").ok_or_else(|| {
        invalid(
            file,
            "z",
            "a column `z`: the penetration of the invert in m (positive down)",
        )
    })?;
    let ip = col("P").or_else(|| col("p")).ok_or_else(|| {
        invalid(
            file,
            "P",
            "a column `P`: the soil resistance in N/m (without soil buoyancy)",
        )
    })?;
    let il = col("leg");
    let (mut z, mut p, mut legs) = (Vec::new(), Vec::new(), Vec::new());
    for (row, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |i: usize, name: &str| -> Result<f64, SceneError> {
            cells
                .get(i)
                .and_then(|c| c.parse::<f64>().ok())
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    invalid(
                        file,
                        format!("row {}, column {name}", row + 1),
                        "a finite number",
                    )
                })
        };
        z.push(num(iz, "z")?);
        p.push(num(ip, "P")?);
        if let Some(il) = il {
            legs.push(num(il, "leg")? as i64);
        }
    }
    if z.len() < MIN_POINTS {
        return Err(invalid(
            file,
            "rows",
            format!("at least {MIN_POINTS} points of the test, got {}", z.len()),
        ));
    }
    if !legs.is_empty() {
        let mut start = 0;
        for i in 1..=z.len() {
            if i == z.len() || legs[i] != legs[start] {
                let leg = &z[start..i];
                let up = leg.windows(2).any(|w| w[1] < w[0]);
                let down = leg.windows(2).any(|w| w[1] > w[0]);
                if up && down {
                    return Err(invalid(
                        file,
                        format!("leg {} (rows {} to {})", legs[start], start + 1, i),
                        "a leg monotonic in z (one direction of travel; start a new leg at each reversal)",
                    ));
                }
                start = i;
            }
        }
    }
    Ok(TestData {
        file: file.to_string(),
        z,
        p,
    })
}

/// The law's force at each point of the test, walked from an untouched node (`None` if the
/// parameters are not valid).
pub fn forward(params: &RqParams, z: &[f64]) -> Option<Vec<f64>> {
    let law = RandolphQuiggin::new(*params).ok()?;
    let max_step = params.diameter / 500.0;
    let mut h = RqHistory::untouched(0.0);
    let mut prev = 0.0;
    let mut out = Vec::with_capacity(z.len());
    for &target in z {
        let n = ((target - prev).abs() / max_step).ceil().max(1.0) as usize;
        let mut p = 0.0;
        for k in 1..=n {
            let zk = if k == n {
                target
            } else {
                prev + (target - prev) * k as f64 / n as f64
            };
            let t = law.evaluate(&h, zk);
            p = t.p;
            h = t.next;
        }
        out.push(p);
        prev = target;
    }
    Some(out)
}

/// A parameter's value by key.
fn get(p: &RqParams, key: &str) -> f64 {
    match key {
        "su0" => p.su0,
        "su_gradient" => p.su_gradient,
        "a" => p.a,
        "b" => p.b,
        "k_max" => p.k_max,
        "f_suc" => p.f_suc,
        "lambda_suc" => p.lambda_suc,
        _ => p.lambda_rep,
    }
}

fn set(p: &mut RqParams, key: &str, v: f64) {
    match key {
        "su0" => p.su0 = v,
        "su_gradient" => p.su_gradient = v,
        "a" => p.a = v,
        "b" => p.b = v,
        "k_max" => p.k_max = v,
        "f_suc" => p.f_suc = v,
        "lambda_suc" => p.lambda_suc = v,
        _ => p.lambda_rep = v,
    }
}

fn bounded(key: &str) -> bool {
    matches!(key, "b" | "f_suc")
}

/// Parameter value → fitting coordinate.
fn to_x(key: &str, v: f64) -> f64 {
    if bounded(key) {
        let v = v.clamp(1e-9, 1.0 - 1e-9);
        (v / (1.0 - v)).ln()
    } else {
        v.ln()
    }
}

/// Fitting coordinate → parameter value.
fn from_x(key: &str, x: f64) -> f64 {
    if bounded(key) {
        1.0 / (1.0 + (-x).exp())
    } else {
        x.exp()
    }
}

/// One fitted parameter's report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Determination {
    /// The key.
    pub name: String,
    /// The start value.
    pub start: f64,
    /// The fitted value.
    pub value: f64,
    /// RMS change of `P` for a 1 % change of the parameter, relative to the peak `|P|`.
    pub sensitivity_per_percent: f64,
    /// Relative standard error from the residual's scatter (0 for a noiseless test).
    pub relative_standard_error: f64,
    /// The relative standard error a scatter of 0.1 % of the peak force would give (the test's
    /// power to determine the parameter, whatever its own scatter; NaN when not determined).
    pub error_at_reference_scatter: f64,
    /// Correlation with each fitted parameter, in the order of `fitted`.
    pub correlation: Vec<f64>,
    /// `well determined`, `weakly determined` or `not determined`.
    pub verdict: String,
}

/// The result of a calibration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Calibration {
    /// The fitted parameters (all of them; the fixed ones at the start's values).
    pub params: RqParams,
    /// The fitted keys.
    pub fitted: Vec<String>,
    /// RMS misfit at the start and at the fit, N/m.
    pub rms_start: f64,
    /// RMS misfit at the fit, N/m.
    pub rms: f64,
    /// The fit's RMS misfit relative to the peak `|P_test|`.
    pub rms_relative: f64,
    /// The law's force at each point with the fitted parameters, N/m.
    pub model_p: Vec<f64>,
    /// The law's force at each point with the start parameters, N/m.
    pub start_p: Vec<f64>,
    /// Each fitted parameter's determination.
    pub determination: Vec<Determination>,
    /// Misfit evaluations.
    pub evaluations: u64,
}

#[derive(Clone, Copy)]
struct Misfit<'a> {
    data: &'a TestData,
    start: RqParams,
    keys: &'a [String],
    evaluations: &'a std::sync::atomic::AtomicU64,
}

impl Misfit<'_> {
    fn params(&self, x: &[f64]) -> RqParams {
        let mut p = self.start;
        for (k, &xi) in self.keys.iter().zip(x) {
            set(&mut p, k, from_x(k, xi));
        }
        p
    }

    fn rms(&self, p: &RqParams) -> f64 {
        self.evaluations
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        match forward(p, &self.data.z) {
            Some(m) => {
                let s: f64 = m
                    .iter()
                    .zip(&self.data.p)
                    .map(|(a, b)| (a - b).powi(2))
                    .sum();
                (s / m.len() as f64).sqrt()
            }
            None => f64::INFINITY,
        }
    }
}

impl CostFunction for Misfit<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, x: &Vec<f64>) -> Result<f64, argmin::core::Error> {
        let r = self.rms(&self.params(x));
        Ok(if r.is_finite() { r } else { 1e300 })
    }
}

fn simplex(x0: &[f64]) -> Vec<Vec<f64>> {
    let mut s = vec![x0.to_vec()];
    for k in 0..x0.len() {
        let mut v = x0.to_vec();
        v[k] += 0.1;
        s.push(v);
    }
    s
}

/// Fits the keys `fit` of `start` to the test (see the module docs). `file` names the start table
/// for errors.
pub fn calibrate(
    data: &TestData,
    start: RqParams,
    fit: &[String],
    file: &str,
) -> Result<Calibration, AppError> {
    if fit.is_empty() {
        return Err(invalid(file, "fit", format!("at least one of {FITTABLE:?}")).into());
    }
    for (i, k) in fit.iter().enumerate() {
        if !FITTABLE.contains(&k.as_str()) {
            return Err(invalid(
                file,
                format!("fit[{i}]"),
                format!("one of {FITTABLE:?}, got `{k}`"),
            )
            .into());
        }
        if fit[..i].contains(k) {
            return Err(invalid(file, format!("fit[{i}]"), format!("`{k}` once")).into());
        }
        let v = get(&start, k);
        let ok = if bounded(k) {
            v > 0.0 && v < 1.0
        } else {
            v > 0.0
        };
        if !ok {
            return Err(invalid(
                file,
                format!("seabed.{k}"),
                format!(
                    "a start value {} to fit from (got {v})",
                    if bounded(k) {
                        "strictly between 0 and 1"
                    } else {
                        "> 0"
                    }
                ),
            )
            .into());
        }
    }
    RandolphQuiggin::new(start)
        .map_err(|e| AppError::from(invalid(file, format!("seabed.{}", e.key), e.expected)))?;
    let counter = std::sync::atomic::AtomicU64::new(0);
    let cost = Misfit {
        data,
        start,
        keys: fit,
        evaluations: &counter,
    };
    let x0: Vec<f64> = fit.iter().map(|k| to_x(k, get(&start, k))).collect();
    let mut best = x0.clone();
    for _ in 0..2 {
        let solver = NelderMead::new(simplex(&best))
            .with_sd_tolerance(1e-12)
            .map_err(|e| AppError::Run {
                file: data.file.clone(),
                message: format!("the optimiser: {e}"),
            })?;
        let res = Executor::new(cost, solver)
            .configure(|s| s.max_iters(400 * fit.len() as u64))
            .run()
            .map_err(|e| AppError::Run {
                file: data.file.clone(),
                message: format!("the optimiser: {e}"),
            })?;
        if let Some(p) = res.state().get_best_param() {
            best = p.clone();
        }
    }
    let params = cost.params(&best);
    let model_p = forward(&params, &data.z).unwrap_or_default();
    let start_p = forward(&start, &data.z).unwrap_or_default();
    let rms = cost.rms(&params);
    let peak = data
        .p
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    let determination = determine(&cost, &best, &model_p, peak);
    Ok(Calibration {
        params,
        fitted: fit.to_vec(),
        rms_start: cost.rms(&start),
        rms,
        rms_relative: rms / peak,
        model_p,
        start_p,
        determination,
        evaluations: counter.load(std::sync::atomic::Ordering::Relaxed),
    })
}

/// The sensitivity, standard errors and correlations at the fit `x` (see the module docs).
fn determine(cost: &Misfit<'_>, x: &[f64], model: &[f64], peak: f64) -> Vec<Determination> {
    let (n, m) = (model.len(), x.len());
    let h = 1e-3;
    let mut jac = nalgebra::DMatrix::<f64>::zeros(n, m);
    for k in 0..m {
        let mut xp = x.to_vec();
        let mut xm = x.to_vec();
        // The step in ln v (for a logit coordinate, the equivalent step in ln v at the value).
        let key = &cost.keys[k];
        let v = from_x(key, x[k]);
        let dx = if bounded(key) { h / (1.0 - v) } else { h };
        xp[k] += dx;
        xm[k] -= dx;
        let (fp, fm) = (
            forward(&cost.params(&xp), &cost.data.z),
            forward(&cost.params(&xm), &cost.data.z),
        );
        if let (Some(fp), Some(fm)) = (fp, fm) {
            for i in 0..n {
                jac[(i, k)] = (fp[i] - fm[i]) / (2.0 * h);
            }
        }
    }
    let resid: f64 = model
        .iter()
        .zip(&cost.data.p)
        .map(|(a, b)| (a - b).powi(2))
        .sum();
    let sens: Vec<f64> = (0..m)
        .map(|k| jac.column(k).norm() / (n as f64).sqrt() / peak * 0.01)
        .collect();
    // Standard errors and correlations among the parameters the test exercises.
    let live: Vec<usize> = (0..m).filter(|&k| sens[k] >= 1e-5).collect();
    let sub = nalgebra::DMatrix::from_fn(n, live.len(), |i, j| jac[(i, live[j])]);
    let dof = n.saturating_sub(live.len()).max(1) as f64;
    let s2 = resid / dof;
    let inv = (sub.transpose() * &sub).try_inverse();
    let at = |k: usize| live.iter().position(|&l| l == k);
    (0..m)
        .map(|k| {
            let cov = |a: usize, b: usize| match (&inv, at(a), at(b)) {
                (Some(c), Some(i), Some(j)) => c[(i, j)],
                _ => f64::NAN,
            };
            let correlation: Vec<f64> = (0..m)
                .map(|j| cov(k, j) / (cov(k, k) * cov(j, j)).sqrt())
                .collect();
            let se = (cov(k, k) * s2).sqrt();
            // The standard error a scatter of 0.1 % of the peak force would give.
            let at_reference = 1e-3 * peak * cov(k, k).sqrt();
            let verdict = if sens[k] < 1e-5 {
                "not determined"
            } else if at_reference < 0.01 {
                "well determined"
            } else {
                "weakly determined"
            };
            Determination {
                name: cost.keys[k].clone(),
                start: get(&cost.start, &cost.keys[k]),
                value: from_x(&cost.keys[k], x[k]),
                sensitivity_per_percent: sens[k],
                relative_standard_error: se,
                error_at_reference_scatter: at_reference,
                correlation,
                verdict: verdict.into(),
            }
        })
        .collect()
}

/// The fitted `[seabed]` table as TOML, with a comment header saying what was fitted and how well.
pub fn seabed_toml(c: &Calibration, test: &str) -> String {
    let p = &c.params;
    let mut s = format!(
        "# Randolph–Quiggin parameters fitted by `catena calibrate` to {test}.\n\
         # Fitted: {}; the others as in the start table. RMS misfit {:.6e} N/m ({:.3} % of the peak force; {:.6e} N/m at the start).\n",
        c.fitted.join(", "),
        c.rms,
        100.0 * c.rms_relative,
        c.rms_start
    );
    for d in &c.determination {
        s.push_str(&format!(
            "# {}: {:.6e} (start {:.6e}), {}: a 1 % change moves P by {:.3e} of the peak\n",
            d.name, d.value, d.start, d.verdict, d.sensitivity_per_percent
        ));
    }
    s.push_str(&format!(
        "[seabed]\nmodel = \"randolph-quiggin\"\ndiameter = {:?}\nsu0 = {:?}\nsu_gradient = {:?}\na = {:?}\nb = {:?}\nk_max = {:?}\nf_suc = {:?}\nlambda_suc = {:?}\nlambda_rep = {:?}\n",
        p.diameter, p.su0, p.su_gradient, p.a, p.b, p.k_max, p.f_suc, p.lambda_suc, p.lambda_rep
    ));
    if p.liftoff_smoothing {
        s.push_str("liftoff_smoothing = true\n");
    }
    if let Some(d) = &p.degradation {
        s.push_str(&format!(
            "\n[seabed.degradation]\nsensitivity = {:?}\nductility = {:?}\n",
            d.sensitivity, d.ductility
        ));
        if let Some(r) = &d.regain {
            s.push_str(&format!(
                "regain_t50 = {:?}\nregain_exponent = {:?}\n",
                r.t50, r.exponent
            ));
        }
    }
    s
}
