//! `splinelab deform`: deform a grid of Bézier patches by flow vectors at
//! their sample points (seed 001 eq 4), correct the joins (§2.3), and write
//! the surface as JSON plus an SVG picture.
//!
//! Input (JSON):
//!
//! ```text
//! { "degree": 3, "nu": 2, "nv": 2,
//!   "patches": [ [[x,y,z], … (n+1)² points P_ij row-major], … nu·nv patches, row-major over (p, q) ],
//!   "samples": {"family": "equispaced"}   or   {"u": [...], "v": [...]},
//!   "flow": [ [[fx,fy,fz], … (n+1)² vectors at R(u_a, v_b), row-major], … one list per patch ],
//!   "solver": "kronecker-marco-martinez",   (optional; or "full-lu", "kronecker-lu")
//!   "correct": true }                       (optional, default true; needs degree ≥ 3)
//! ```
//!
//! Everything is read, validated and computed before the output directory is
//! created; bad input leaves nothing behind.

use crate::error::CliError;
use crate::input::{input_error, parse_json, read_text};
use crate::outln;
use crate::output::{PendingFiles, emit, print_json};
use crate::path_text::path_text;
use crate::report::bernstein_inverse::surface_chart;
use clap::Args;
use serde::Deserialize;
use serde_json::json;
use splinelab::surface_deformation::bv_solve::TensorSolver;
use splinelab::surface_deformation::continuity::correct_continuity;
use splinelab::surface_deformation::inverse_mapping::{SampleGrid, deform_grid};
use splinelab::surface_deformation::patch::{Patch, PatchGrid, Point3};
use splinelab::surface_deformation::vandermonde::NodeFamily;
use splinelab_verify::deform::{
    Defects, PushParams, defects, grid_to_f64, push_surfaces, sample_residual,
};
use std::path::{Path, PathBuf};

/// Largest accepted patch degree (a 31 × 31 sample grid per patch).
pub const MAX_DEGREE: usize = 30;
/// Largest accepted number of patches.
pub const MAX_PATCHES: usize = 10_000;

/// Arguments of `splinelab deform`.
#[derive(Debug, Args)]
pub struct DeformArgs {
    /// Input JSON {degree, nu, nv, patches, samples, flow[, solver, correct]}: the patch grid, the
    /// sample parameters ({"family": "equispaced"} or {"u": [...], "v": [...]}) and flow vectors.
    #[arg(long, required_unless_present = "example", conflicts_with = "example")]
    pub input: Option<PathBuf>,
    /// Use the seed-001 experiment instead of --input: 10 × 10 bicubic patches on z = 0 pushed by a
    /// Gaussian (its input is written to DIR/input.json).
    #[arg(long)]
    pub example: bool,
    /// Output directory (created): deformed.json and deformed.svg.
    #[arg(long)]
    pub out: PathBuf,
    /// Print a JSON summary on stdout.
    #[arg(long)]
    pub json: bool,
}

/// Sample parameters: a node family or explicit lists.
#[derive(Debug, Clone, Deserialize, serde::Serialize)]
#[serde(untagged, try_from = "RawSamples")]
pub enum SamplesSpec {
    /// The same node family in `u` and `v`.
    Family {
        /// `equispaced`, `chebyshev-lobatto` or `chebyshev-gauss`.
        family: NodeFamily,
    },
    /// Explicit increasing parameters in `[0, 1]`.
    Explicit {
        /// `u_0 < … < u_n`.
        u: Vec<f64>,
        /// `v_0 < … < v_n`.
        v: Vec<f64>,
    },
}

/// `samples` as written: exactly one of the two forms, no other key.
#[derive(Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "samples as {\"family\": NAME} or {\"u\": [...], \"v\": [...]}"
)]
struct RawSamples {
    family: Option<NodeFamily>,
    u: Option<Vec<f64>>,
    v: Option<Vec<f64>>,
}

impl TryFrom<RawSamples> for SamplesSpec {
    type Error = &'static str;
    fn try_from(raw: RawSamples) -> Result<Self, Self::Error> {
        match raw {
            RawSamples {
                family: Some(family),
                u: None,
                v: None,
            } => Ok(SamplesSpec::Family { family }),
            RawSamples {
                family: None,
                u: Some(u),
                v: Some(v),
            } => Ok(SamplesSpec::Explicit { u, v }),
            _ => Err("samples: give either \"family\" or both \"u\" and \"v\""),
        }
    }
}

/// The input file.
#[derive(Debug, Clone, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct DeformInput {
    /// Patch degree `n`.
    pub degree: usize,
    /// Patches in `u`.
    pub nu: usize,
    /// Patches in `v`.
    pub nv: usize,
    /// Control nets.
    pub patches: Vec<Vec<[f64; 3]>>,
    /// Sample parameters.
    pub samples: SamplesSpec,
    /// Flow vectors per patch.
    pub flow: Vec<Vec<[f64; 3]>>,
    /// Solver for eq 4.
    #[serde(default = "default_solver")]
    pub solver: String,
    /// Apply the §2.3 correction.
    #[serde(default = "default_true")]
    pub correct: bool,
}

fn default_solver() -> String {
    TensorSolver::KroneckerMarcoMartinez.name().into()
}

fn default_true() -> bool {
    true
}

fn points(v: &[[f64; 3]]) -> Vec<Point3<f64>> {
    v.iter().map(|p| Point3::new(p[0], p[1], p[2])).collect()
}

/// What `deform` computed, before anything is written.
pub struct Outcome {
    input: DeformInput,
    deformed: PatchGrid<f64>,
    corrected: Option<PatchGrid<f64>>,
    samples: SampleGrid<f64>,
    residual: f64,
    before: Defects,
    after: Option<Defects>,
}

impl Outcome {
    /// The deformed patch grid (before any join correction).
    pub fn deformed(&self) -> &PatchGrid<f64> {
        &self.deformed
    }

    /// The sample parameters the flows were applied at.
    pub fn samples(&self) -> &SampleGrid<f64> {
        &self.samples
    }

    /// `max |R'(u_a, v_b) − (R(u_a, v_b) + F_ab)|` over every patch and
    /// sample, evaluated in f64: how well the deformed grid meets eq 4.
    pub fn residual(&self) -> f64 {
        self.residual
    }
}

/// Validates `input` (from the file `source`: degree, patch count, solver,
/// nets, samples, flows) and deforms the grid, then corrects the joins if
/// asked. Errors in the input are [`CliError::Input`] naming `source`.
pub fn compute(input: DeformInput, source: &Path) -> Result<Outcome, CliError> {
    let bad = |why: String| input_error(source, why);
    if !(1..=MAX_DEGREE).contains(&input.degree) {
        return Err(bad(format!(
            "degree {} is outside 1..={MAX_DEGREE}",
            input.degree
        )));
    }
    if input.nu.saturating_mul(input.nv) > MAX_PATCHES {
        return Err(bad(format!(
            "{}×{} patches exceed {MAX_PATCHES}",
            input.nu, input.nv
        )));
    }
    let solver: TensorSolver = input.solver.parse().map_err(&bad)?;
    let patches = input
        .patches
        .iter()
        .enumerate()
        .map(|(k, c)| {
            Patch::new(input.degree, points(c)).map_err(|e| bad(format!("patch {k}: {e}")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let surface = PatchGrid::new(input.nu, input.nv, patches).map_err(|e| bad(e.to_string()))?;
    let samples = match &input.samples {
        SamplesSpec::Family { family } => SampleGrid::from_family(*family, input.degree),
        SamplesSpec::Explicit { u, v } => SampleGrid::new(u.clone(), v.clone()),
    }
    .map_err(|e| bad(e.to_string()))?;
    let flows: Vec<Vec<Point3<f64>>> = input.flow.iter().map(|f| points(f)).collect();
    let deformed =
        deform_grid(&surface, &samples, &flows, solver).map_err(|e| bad(e.to_string()))?;
    let residual =
        sample_residual(&surface, &deformed, &samples, &flows).map_err(CliError::numerical)?;
    let before = defects(&deformed).map_err(CliError::numerical)?;
    let corrected = if input.correct {
        Some(correct_continuity(&deformed).map_err(|e| bad(e.to_string()))?)
    } else {
        None
    };
    let after = corrected
        .as_ref()
        .map(defects)
        .transpose()
        .map_err(CliError::numerical)?;
    check_finite(
        &deformed,
        corrected.as_ref(),
        residual,
        &before,
        after.as_ref(),
    )?;
    Ok(Outcome {
        input,
        deformed,
        corrected,
        samples,
        residual,
        before,
        after,
    })
}

/// Refuses a result that overflowed (flows near the f64 limit): a
/// non-finite control point, residual or join defect would otherwise be
/// written as JSON `null` and printed as a mismatch of 0.
fn check_finite(
    deformed: &PatchGrid<f64>,
    corrected: Option<&PatchGrid<f64>>,
    residual: f64,
    before: &Defects,
    after: Option<&Defects>,
) -> Result<(), CliError> {
    let grid_ok = |g: &PatchGrid<f64>| {
        g.patches()
            .iter()
            .all(|p| p.control().iter().all(|q| q.iter().all(|x| x.is_finite())))
    };
    let defects_ok = |d: &Defects| {
        d.position.is_finite() && d.tangent.is_finite() && d.tangent_relative.is_finite()
    };
    let what = if !grid_ok(deformed) {
        Some("the deformed control points")
    } else if corrected.is_some_and(|g| !grid_ok(g)) {
        Some("the corrected control points")
    } else if !residual.is_finite() {
        Some("the sample residuals")
    } else if !defects_ok(before) || after.is_some_and(|d| !defects_ok(d)) {
        Some("the join defects")
    } else {
        None
    };
    match what {
        Some(w) => Err(CliError::Numerical(format!(
            "overflow: not finite in f64: {w} (flows or control points too large; \
             scale the input down)"
        ))),
        None => Ok(()),
    }
}

/// The seed-001 experiment as an input file.
fn example_input() -> Result<DeformInput, CliError> {
    let p = PushParams::default();
    let s = push_surfaces::<f64>(&p).map_err(CliError::numerical)?;
    let flow = s
        .flows
        .iter()
        .map(|f| f.iter().map(|v| [v.x, v.y, v.z]).collect())
        .collect();
    Ok(DeformInput {
        degree: p.degree,
        nu: p.patches,
        nv: p.patches,
        patches: grid_to_f64(&s.initial),
        samples: SamplesSpec::Family { family: p.nodes },
        flow,
        solver: p.solver.name().into(),
        correct: true,
    })
}

/// Parses the input file's text (`path` names it in errors); [`compute`]
/// validates the contents.
pub fn parse_input(path: &Path, text: &str) -> Result<DeformInput, CliError> {
    parse_json(path, text)
}

/// Files written into `dir` but not yet in place ([`PendingFiles`]), and
/// `dir` itself when this run created it: dropped uncommitted (a later step
/// failed, stdout included), the temporaries go and so does the new folder.
struct StagedOutputs {
    files: Option<PendingFiles>,
    created: Option<PathBuf>,
}

impl StagedOutputs {
    /// Creates `dir` if needed and writes `files` beside their targets.
    fn write(dir: &Path, files: &[(PathBuf, String)]) -> Result<Self, CliError> {
        let mut staged = StagedOutputs {
            files: None,
            created: (!dir.exists()).then(|| dir.to_path_buf()),
        };
        std::fs::create_dir_all(dir).map_err(|source| CliError::Output {
            path: dir.to_path_buf(),
            source,
        })?;
        let contents: Vec<(&Path, &[u8])> = files
            .iter()
            .map(|(p, c)| (p.as_path(), c.as_bytes()))
            .collect();
        staged.files = Some(PendingFiles::write(&contents)?);
        Ok(staged)
    }

    /// Moves the files into place; the folder stays.
    fn commit(mut self) -> Result<(), CliError> {
        if let Some(files) = self.files.take() {
            files.commit()?;
        }
        self.created = None;
        Ok(())
    }
}

impl Drop for StagedOutputs {
    fn drop(&mut self) {
        drop(self.files.take());
        if let Some(dir) = &self.created {
            let _ = std::fs::remove_dir(dir);
        }
    }
}

/// Runs `splinelab deform`.
pub fn run(args: &DeformArgs) -> Result<(), CliError> {
    let (input, source) = match &args.input {
        Some(path) => (parse_input(path, &read_text(path)?)?, path.clone()),
        None => (example_input()?, PathBuf::from("(built-in example)")),
    };
    let out = compute(input, &source)?;
    let final_grid = out.corrected.as_ref().unwrap_or(&out.deformed);
    let nets = grid_to_f64(final_grid);
    let title = if out.corrected.is_some() {
        "Deformed surface (continuity corrected)"
    } else {
        "Deformed surface"
    };
    let chart = surface_chart("deformed", title, &nets, out.input.nv, out.input.degree, "")?;
    let svg = chart
        .render_svg()
        .map_err(|e| CliError::Chart("deformed".into(), e.to_string()))?;
    let (u, v) = (out.samples.u().to_vec(), out.samples.v().to_vec());
    let doc = json!({
        "degree": out.input.degree,
        "nu": out.input.nu,
        "nv": out.input.nv,
        "solver": out.input.solver,
        "samples": {"u": u, "v": v},
        "corrected": out.corrected.is_some(),
        "patches": nets,
        "patches_before_correction": out.corrected.as_ref().map(|_| grid_to_f64(&out.deformed)),
        "max_sample_residual": out.residual,
        "join_defects_before_correction": out.before,
        "join_defects_after_correction": out.after,
    });
    let text = serde_json::to_string_pretty(&doc).map_err(CliError::numerical)?;
    let example = if args.example {
        Some(serde_json::to_string(&out.input).map_err(CliError::numerical)?)
    } else {
        None
    };
    let mut files = vec![
        (args.out.join("deformed.json"), text),
        (args.out.join("deformed.svg"), svg),
    ];
    if let Some(e) = example {
        files.push((args.out.join("input.json"), e));
    }
    // All computed: only now touch the file system; the files move into
    // place only after the summary reached stdout (which can fail too).
    let staged = StagedOutputs::write(&args.out, &files)?;
    let files: Vec<&PathBuf> = files.iter().map(|(p, _)| p).collect();
    if args.json {
        print_json(&json!({
            "input": path_text(&source),
            "files": files.iter().map(|f| path_text(f)).collect::<Vec<_>>(),
            "degree": out.input.degree,
            "patches": out.input.nu * out.input.nv,
            "solver": out.input.solver,
            "corrected": out.corrected.is_some(),
            "max_sample_residual": out.residual,
            "join_defects_before_correction": out.before,
            "join_defects_after_correction": out.after,
        }))?;
    } else {
        let mut text = String::new();
        outln!(
            text,
            "deformed {}×{} degree-{} patches with {}",
            out.input.nu,
            out.input.nv,
            out.input.degree,
            out.input.solver
        );
        outln!(text, "max sample residual      {:.3e}", out.residual);
        outln!(
            text,
            "cross-tangent mismatch   {:.3e} (before correction)",
            out.before.tangent
        );
        if let Some(a) = &out.after {
            outln!(
                text,
                "cross-tangent mismatch   {:.3e} (after correction)",
                a.tangent
            );
        }
        for f in &files {
            outln!(text, "wrote {}", f.display());
        }
        emit(&text)?;
    }
    staged.commit()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> DeformInput {
        let net: Vec<[f64; 3]> = (0..4)
            .map(|k| [(k / 2) as f64, (k % 2) as f64, 0.0])
            .collect();
        DeformInput {
            degree: 1,
            nu: 1,
            nv: 1,
            patches: vec![net],
            samples: SamplesSpec::Family {
                family: NodeFamily::Equispaced,
            },
            flow: vec![vec![[0.0, 0.0, 1.0]; 4]],
            solver: default_solver(),
            correct: false,
        }
    }

    #[test]
    fn bad_input_is_refused_before_anything_is_written() {
        let dir =
            std::env::temp_dir().join(format!("splinelab_deform_test_{}", std::process::id()));
        let bad_file = dir.with_extension("json");
        type Change = Box<dyn Fn(&mut DeformInput)>;
        let cases: Vec<Change> = vec![
            Box::new(|i| {
                i.samples = SamplesSpec::Explicit {
                    u: vec![0.5, 0.5],
                    v: vec![0.0, 1.0],
                }
            }),
            Box::new(|i| {
                i.samples = SamplesSpec::Explicit {
                    u: vec![0.0, 1.5],
                    v: vec![0.0, 1.0],
                }
            }),
            Box::new(|i| i.flow[0][2][1] = f64::NAN),
            Box::new(|i| i.patches[0][1][0] = f64::INFINITY),
            Box::new(|i| i.flow[0].pop().map(drop).unwrap_or(())),
            Box::new(|i| i.nv = 2),
            Box::new(|i| i.solver = "cholesky".into()),
            Box::new(|i| i.correct = true),
        ];
        for (k, change) in cases.iter().enumerate() {
            let mut input = tiny();
            change(&mut input);
            // NaN/inf cannot be written as JSON; test compute() directly for those.
            assert!(
                matches!(compute(input, &bad_file), Err(CliError::Input { .. })),
                "case {k}"
            );
        }
        std::fs::write(
            &bad_file,
            serde_json::to_string(&{
                let mut i = tiny();
                i.samples = SamplesSpec::Explicit {
                    u: vec![0.0, 0.0],
                    v: vec![0.0, 1.0],
                };
                i
            })
            .unwrap(),
        )
        .unwrap();
        let args = DeformArgs {
            input: Some(bad_file.clone()),
            example: false,
            out: dir.clone(),
            json: false,
        };
        assert!(matches!(run(&args), Err(CliError::Input { .. })));
        assert!(!dir.exists(), "nothing may be written on bad input");
        std::fs::write(&bad_file, "{\"degree\": 1}").unwrap();
        assert!(matches!(run(&args), Err(CliError::Input { .. })));
        assert!(!dir.exists());
        let _ = std::fs::remove_file(&bad_file);
    }

    #[test]
    fn a_bilinear_patch_lifted_by_one_is_the_lifted_patch() {
        let out = compute(tiny(), Path::new("tiny.json")).unwrap();
        // Degree 1 at corner samples: control points are the samples, so the
        // flow (0, 0, 1) lifts every control point by exactly 1.
        for (k, p) in out.deformed.patch(0, 0).control().iter().enumerate() {
            assert_eq!(*p, Point3::new((k / 2) as f64, (k % 2) as f64, 1.0));
        }
        assert_eq!(out.residual, 0.0);
    }
}
