//! `splinelab cond`: condition numbers of one Vandermonde-type matrix.

use super::prec::{MAX_BITS, Prec, parse_prec};
use crate::budget::{BudgetArgs, Estimate, unit_seconds};
use crate::error::CliError;
use crate::outln;
use crate::output::{emit, print_json};
use crate::with_real;
use clap::Args;
use serde_json::json;
use splinelab::matrix_condition::ConditionError;
use splinelab::scalar::Real;
use splinelab::surface_deformation::vandermonde::NodeFamily;
use splinelab_verify::conditioning::{Basis, CondCase, StudyError, condition_numbers};

/// Largest degree accepted: a 501 × 501 matrix, already minutes in MPFR.
pub const MAX_DEGREE: usize = 500;

/// Arguments of `splinelab cond`.
#[derive(Debug, Args)]
pub struct CondArgs {
    /// Polynomial degree n (1..=500); the matrix is (n+1)×(n+1), or (n+1)²×(n+1)² with --tensor.
    #[arg(long, value_parser = super::whole::<usize>)]
    pub degree: usize,
    /// Node family: equispaced (j/n), chebyshev-lobatto ((1−cos(πj/n))/2) or chebyshev-gauss ((1−cos(π(2j+1)/(2n+2)))/2).
    #[arg(long, value_parser = parse_nodes)]
    pub nodes: NodeFamily,
    /// Basis of the Vandermonde matrix.
    #[arg(long, value_enum, default_value = "bernstein")]
    pub basis: BasisArg,
    /// The tensor matrix B_u ⊗ B_v of seed 001 eq 2 on the grid of the nodes.
    #[arg(long)]
    pub tensor: bool,
    /// Working precision: f64, or MPFR bits (16..=2048; runs at the next compiled precision, at most 2× the bits).
    #[arg(long, default_value = "f64", value_parser = parse_prec)]
    pub prec: Prec,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// The run-time and memory budget.
    #[command(flatten)]
    pub budget: BudgetArgs,
}

/// `--basis` values.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum BasisArg {
    /// Bernstein basis B_i^n(t).
    Bernstein,
    /// Monomial basis tᶦ.
    Monomial,
}

fn parse_nodes(s: &str) -> Result<NodeFamily, String> {
    s.parse()
        .map_err(|e: splinelab::surface_deformation::vandermonde::VandermondeError| e.to_string())
}

/// The cost of `cond`: an SVD and an inverse of the (n+1)×(n+1) matrix
/// (the tensor case uses the Kronecker identity, same cost), about `N³`
/// work units (measured: degree 80 takes 0.4 s at 64 bits, 4.5 s at 2048).
pub fn estimate(degree: usize, bits: u32) -> Estimate {
    let n = degree as f64 + 1.0;
    Estimate {
        seconds: n.powi(3) * unit_seconds(bits),
        bytes: 4.0 * n * n * crate::budget::number_bytes(bits),
        what: format!("a {n}×{n} SVD at {bits} bits"),
    }
}

/// How far the printed condition numbers can be trusted: the SVD's `σ_min`
/// is only known to `≈ N·u·cond₂` relative (backward stability, see
/// [`splinelab::matrix_condition::cond2`]), so `cond₂` has about
/// `−log10(N·u·cond₂)` correct digits at unit roundoff `u`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trust {
    /// Estimated correct significant digits, `0..=` the printed digits.
    pub digits: f64,
    /// The `--prec` that would give every printed f64 digit (17), when the
    /// working precision does not: `log2(N·cond₂) + 64` bits, rounded up to a
    /// multiple of 32. `None` when the digits are already there.
    pub suggested_bits: Option<u32>,
}

impl Trust {
    /// The trust in `cond₂ = cond2` of an `n × n` matrix computed at `prec`.
    pub fn of(cond2: f64, n: usize, prec: Prec) -> Trust {
        let bits = prec.working_bits();
        let max_digits = prec.digits() as f64;
        // log10(N u cond₂) with u = 2^−bits, in logs so that MPFR-sized
        // condition numbers (beyond f64's range) still give a finite estimate.
        let log10_amp =
            (n as f64).log10() + cond2.log10() - f64::from(bits) * std::f64::consts::LOG10_2;
        let digits = round1((-log10_amp).clamp(0.0, max_digits));
        let suggested_bits = (digits < 16.0).then(|| {
            let need = ((n as f64).log2() + cond2.log2() + 64.0).min(f64::from(MAX_BITS));
            ((need / 32.0).ceil() as u32 * 32).max(64)
        });
        Trust {
            digits,
            suggested_bits,
        }
    }

    /// One line of advice for the table.
    pub fn advice(&self, prec: Prec) -> String {
        match self.suggested_bits {
            Some(b) => format!(
                "trust      cond₂ has about {} correct digits (it amplifies {prec}'s rounding); --prec {b} gives all 17",
                self.digits
            ),
            None => format!("trust      cond₂ has about {} correct digits", self.digits),
        }
    }
}

fn round1(x: f64) -> f64 {
    (x * 10.0).round() / 10.0
}

/// The error of a failed computation, with the precision to try next: a
/// matrix singular at `p` bits has `cond₂ ≳ 2^p`, so doubling `p` resolves
/// condition numbers up to `2^{2p}`.
fn singular_advice(e: &StudyError, case: &CondCase, prec: Prec) -> CliError {
    let bits = prec.working_bits();
    let hint = match e {
        StudyError::Condition(ConditionError::Singular) if bits >= MAX_BITS => format!(
            "cond₂ exceeds about 2^{bits} ≈ 1e{:.0}, beyond the largest --prec ({MAX_BITS})",
            f64::from(bits) * std::f64::consts::LOG10_2
        ),
        StudyError::Condition(ConditionError::Singular) => format!(
            "cond₂ exceeds about 2^{bits} ≈ 1e{:.0}, which {prec} cannot resolve: try --prec {}",
            f64::from(bits) * std::f64::consts::LOG10_2,
            (2 * bits).div_ceil(32).saturating_mul(32).min(MAX_BITS)
        ),
        _ => "try a higher --prec".to_string(),
    };
    CliError::Numerical(format!(
        "{e} (degree {}, --prec {prec}): {hint}",
        case.degree
    ))
}

/// Runs `splinelab cond`.
pub fn run(args: &CondArgs) -> Result<(), CliError> {
    if !(1..=MAX_DEGREE).contains(&args.degree) {
        return Err(CliError::invalid(
            "--degree",
            format!("{} is outside 1..={MAX_DEGREE}", args.degree),
        ));
    }
    let basis = match args.basis {
        BasisArg::Bernstein => Basis::Bernstein,
        BasisArg::Monomial => Basis::Monomial,
    };
    let case = CondCase {
        degree: args.degree,
        nodes: args.nodes,
        basis,
        tensor: args.tensor,
    };
    let prec = args.prec;
    let _spinner = args
        .budget
        .check(&estimate(args.degree, prec.working_bits()))?;
    let (cond2, cond_inf, cond2_f64) = with_real!(prec, T => {
        let c = condition_numbers::<T>(&case).map_err(|e| singular_advice(&e, &case, prec))?;
        (prec.format(&c.cond2), prec.format(&c.cond_inf), c.cond2.to_f64())
    });
    let trust = Trust::of(cond2_f64, case.matrix_size(), prec);
    if args.json {
        print_json(&json!({
            "degree": case.degree,
            "nodes": case.nodes.name(),
            "basis": basis.name(),
            "tensor": case.tensor,
            "prec": prec.to_string(),
            "working_bits": prec.working_bits(),
            "cond2": cond2,
            "cond_inf": cond_inf,
            "digits_estimate": trust.digits,
            "suggested_prec": trust.suggested_bits,
        }))?;
    } else {
        let mut text = String::new();
        let size = case.matrix_size();
        outln!(
            text,
            "{} Vandermonde, {} nodes, degree {} ({size}×{size}{})",
            basis.name(),
            case.nodes,
            case.degree,
            if case.tensor { ", tensor" } else { "" }
        );
        outln!(
            text,
            "precision  {prec} (computed at {} bits)",
            prec.working_bits()
        );
        outln!(text, "cond_2     {cond2}");
        outln!(text, "cond_inf   {cond_inf}");
        outln!(text, "{}", trust.advice(prec));
        emit(&text)?;
    }
    Ok(())
}
