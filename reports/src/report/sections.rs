//! The registry of report sections, in page order. A study adds one line,
//! saying whether the report profile chooses its cases and whether it
//! reads the clock.

use super::SectionFn;

/// What a section's figures are measured over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cases {
    /// The same cases in every profile: its figures compare across profiles.
    Fixed,
    /// The profile chooses the cases (more degrees, points or sets in the
    /// full report): its figures compare only within one profile.
    ByProfile,
}

/// One section: the function that runs it, what it is measured over, and
/// whether it times anything.
#[derive(Debug, Clone, Copy)]
pub struct Entry {
    /// Runs the study and presents it.
    pub run: SectionFn,
    /// Whether the profile chooses its cases.
    pub cases: Cases,
    /// Whether its figures include wall-clock times: such a section runs
    /// alone (a concurrent section would take cores from what it times);
    /// the others run side by side on the pool.
    pub timed: bool,
}

const fn fixed(run: SectionFn) -> Entry {
    Entry {
        run,
        cases: Cases::Fixed,
        timed: false,
    }
}

const fn by_profile(run: SectionFn) -> Entry {
    Entry {
        run,
        cases: Cases::ByProfile,
        timed: false,
    }
}

/// A section whose figures include timings (runs alone).
const fn timed(entry: Entry) -> Entry {
    Entry {
        timed: true,
        ..entry
    }
}

/// Every section of the report, in the order they appear.
pub const SECTIONS: &[Entry] = &[
    fixed(super::conditioning::section),
    by_profile(super::bezier_eval::section),
    by_profile(super::qi::section),
    timed(by_profile(super::bernstein_inverse::section)),
    by_profile(super::sspline::section),
    by_profile(super::curves::section),
    timed(by_profile(super::update_cost::section)),
    fixed(super::check::section),
    timed(by_profile(super::engine::section)),
    timed(by_profile(super::gridded::section)),
    fixed(super::small_calls::section),
];
