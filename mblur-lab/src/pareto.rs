//! The Pareto check of a comparison: is the exact method the cheapest way to a good image?
//! For every accum or stochastic run that reaches a PSNR floor (40 dB by default), some
//! analytic run (any setting: K intervals, unbounded, the segments and shading ladders)
//! should reach at least its PSNR in at most its wall time. [`check`] decides it for every
//! such run and names the analytic run that does, or, when none does, the analytic run that
//! comes closest: the fastest one at or above the run's PSNR (with its time ratio), else the
//! most accurate one. [`markdown_section`] writes the result as the "Pareto check" section
//! of `results.md`.
//!
//! Only runs that rendered take part (skipped and failed runs are listed by method in the
//! section); a PSNR of `+inf` (an exact match of the reference) is matched only by another
//! `+inf`; a NaN PSNR reaches no floor and matches nothing.

use mblur::Method;

use crate::record::{Outcome, RunRecord};
use crate::report::{fmt_ms, fmt_psnr};

/// The PSNR floor (dB) of the check by default: runs below it are not checked.
pub const DEFAULT_PSNR_FLOOR: f64 = 40.0;

/// One measured run: its label, wall time and PSNR.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// The run's label (`accum 16 times`, `analytic K=4`, ...).
    pub label: String,
    /// Median wall time, seconds.
    pub seconds: f64,
    /// PSNR against the reference, dB.
    pub psnr: f64,
}

impl Point {
    /// True when `self` reaches at least `other`'s PSNR in at most its time.
    pub fn dominates(&self, other: &Point) -> bool {
        self.psnr >= other.psnr && self.seconds <= other.seconds
    }
}

/// The analytic run that comes closest to a run no analytic run dominates.
#[derive(Debug, Clone, PartialEq)]
pub enum Closest {
    /// The fastest analytic run at or above the run's PSNR, and its time over the run's.
    Slower {
        /// The analytic run.
        analytic: Point,
        /// Its wall time divided by the run's (> 1).
        time_ratio: f64,
    },
    /// No analytic run reaches the run's PSNR: the most accurate analytic run.
    LessAccurate(Point),
    /// The comparison has no analytic run that rendered with a PSNR (one that is not NaN).
    NoAnalytic,
}

/// The verdict on one accum or stochastic run.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// This analytic run reaches at least the run's PSNR in at most its time (the fastest
    /// such; the most accurate among equally fast ones).
    Dominated(Point),
    /// No analytic run does; what comes closest.
    NotDominated(Closest),
}

/// An accum or stochastic run at or above the floor and its verdict.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The run.
    pub run: Point,
    /// The verdict.
    pub verdict: Verdict,
}

/// The check of one comparison.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoCheck {
    /// The PSNR floor, dB.
    pub floor: f64,
    /// One row per accum or stochastic run at or above the floor, in ladder order.
    pub rows: Vec<Row>,
    /// Accum and stochastic runs that rendered below the floor (not checked).
    pub below_floor: usize,
    /// Analytic runs that rendered.
    pub analytic_runs: usize,
    /// Runs of the methods involved that did not render: the series (a refused method,
    /// recorded once) or the label (a failed run), and the reason.
    pub not_rendered: Vec<(String, String)>,
}

impl ParetoCheck {
    /// How many checked runs an analytic run dominates.
    pub fn dominated(&self) -> usize {
        self.rows
            .iter()
            .filter(|r| matches!(r.verdict, Verdict::Dominated(_)))
            .count()
    }

    /// True when every checked run is dominated (also when no run reaches the floor).
    pub fn holds(&self) -> bool {
        self.dominated() == self.rows.len()
    }
}

/// The runs of `records` that rendered, with their method.
fn rendered(records: &[RunRecord]) -> impl Iterator<Item = (Method, Point)> + '_ {
    records.iter().filter_map(|r| match &r.outcome {
        Outcome::Done(s) => Some((
            r.entry.options.method(),
            Point {
                label: r.entry.label(),
                seconds: s.seconds,
                psnr: s.metrics.psnr,
            },
        )),
        Outcome::Skipped(_) | Outcome::Failed(_) => None,
    })
}

/// The verdict on `run` given the analytic runs.
pub fn verdict(run: &Point, analytic: &[Point]) -> Verdict {
    let fastest = |pts: &mut dyn Iterator<Item = &Point>| -> Option<Point> {
        pts.min_by(|a, b| {
            a.seconds
                .total_cmp(&b.seconds)
                .then(b.psnr.total_cmp(&a.psnr))
        })
        .cloned()
    };
    if let Some(a) = fastest(&mut analytic.iter().filter(|a| a.dominates(run))) {
        return Verdict::Dominated(a);
    }
    if let Some(a) = fastest(&mut analytic.iter().filter(|a| a.psnr >= run.psnr)) {
        let time_ratio = a.seconds / run.seconds;
        return Verdict::NotDominated(Closest::Slower {
            analytic: a,
            time_ratio,
        });
    }
    let best = analytic.iter().filter(|a| !a.psnr.is_nan()).max_by(|a, b| {
        a.psnr
            .total_cmp(&b.psnr)
            .then(b.seconds.total_cmp(&a.seconds))
    });
    Verdict::NotDominated(match best {
        Some(a) => Closest::LessAccurate(a.clone()),
        None => Closest::NoAnalytic,
    })
}

/// The Pareto check of a comparison's `records` at PSNR `floor` (dB).
pub fn check(records: &[RunRecord], floor: f64) -> ParetoCheck {
    let analytic: Vec<Point> = rendered(records)
        .filter(|(m, _)| *m == Method::Analytic)
        .map(|(_, p)| p)
        .collect();
    let baselines: Vec<Point> = rendered(records)
        .filter(|(m, _)| matches!(m, Method::Accum | Method::Stochastic))
        .map(|(_, p)| p)
        .collect();
    let measured = baselines.len();
    // A NaN PSNR fails `>=` and is left out with the runs below the floor.
    let rows: Vec<Row> = baselines
        .into_iter()
        .filter(|p| p.psnr >= floor)
        .map(|run| Row {
            verdict: verdict(&run, &analytic),
            run,
        })
        .collect();
    let not_rendered = records
        .iter()
        .filter(|r| {
            matches!(
                r.entry.options.method(),
                Method::Analytic | Method::Accum | Method::Stochastic
            )
        })
        .filter_map(|r| match &r.outcome {
            // A method that refuses the scene is run once and recorded once.
            Outcome::Skipped(why) => Some((r.entry.series.clone(), format!("skipped: {why}"))),
            Outcome::Failed(why) => Some((r.entry.label(), format!("failed: {why}"))),
            Outcome::Done(_) => None,
        })
        .collect();
    ParetoCheck {
        floor,
        below_floor: measured - rows.len(),
        rows,
        analytic_runs: analytic.len(),
        not_rendered,
    }
}

fn point_text(p: &Point) -> String {
    format!(
        "{}: {} dB in {} ms",
        p.label,
        fmt_psnr(p.psnr),
        fmt_ms(p.seconds)
    )
}

/// The "Pareto check" section of `results.md` (a `##` heading, a summary line, one table
/// row per checked run, the runs that did not render).
pub fn markdown_section(check: &ParetoCheck) -> String {
    let floor = fmt_psnr(check.floor);
    let mut out = format!(
        "## Pareto check\n\n\
         For every accum or stochastic run at >= {floor} dB: does some analytic run (any \
         setting) reach at least its PSNR in at most its time? {} of {} yes",
        check.dominated(),
        check.rows.len(),
    );
    out.push_str(&format!(
        "; {} run{} below {floor} dB not checked; {} analytic run{}.\n\n",
        check.below_floor,
        if check.below_floor == 1 { "" } else { "s" },
        check.analytic_runs,
        if check.analytic_runs == 1 { "" } else { "s" },
    ));
    if !check.rows.is_empty() {
        out.push_str(
            "| run | PSNR (dB) | time (ms) | dominated? | analytic run |\n\
             |---|---:|---:|---|---|\n",
        );
    }
    for row in &check.rows {
        let (yes, analytic) = match &row.verdict {
            Verdict::Dominated(a) => ("yes", point_text(a)),
            Verdict::NotDominated(Closest::Slower {
                analytic,
                time_ratio,
            }) => (
                "no",
                format!(
                    "fastest at >= its PSNR: {} ({time_ratio:.2}x its time)",
                    point_text(analytic)
                ),
            ),
            Verdict::NotDominated(Closest::LessAccurate(a)) => (
                "no",
                format!("none reaches its PSNR; most accurate: {}", point_text(a)),
            ),
            Verdict::NotDominated(Closest::NoAnalytic) => ("no", "no analytic run".to_string()),
        };
        out.push_str(&format!(
            "| {} | {} | {} | {yes} | {analytic} |\n",
            row.run.label,
            fmt_psnr(row.run.psnr),
            fmt_ms(row.run.seconds),
        ));
    }
    if !check.not_rendered.is_empty() {
        out.push_str("\nNot rendered:\n\n");
        for (label, why) in &check.not_rendered {
            out.push_str(&format!("- {label}: {}\n", why.replace('\n', " ")));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::Metrics;
    use crate::record::{LadderEntry, RunStats};
    use mblur::{AccumOptions, AnalyticOptions, MethodOptions, StochasticOptions};

    fn done(index: usize, entry: LadderEntry, ms: f64, psnr: f64) -> RunRecord {
        let mse = 10f64.powf(-psnr / 10.0);
        RunRecord {
            index,
            entry,
            outcome: Outcome::Done(RunStats {
                seconds: ms * 1e-3,
                repeats: 1,
                heap_bytes: None,
                metrics: Metrics {
                    mse,
                    rmse: mse.sqrt(),
                    psnr,
                    max_abs: mse.sqrt(),
                    ssim: None,
                },
                description: String::new(),
            }),
            image_file: None,
        }
    }

    fn analytic(k: u32) -> LadderEntry {
        let setting = if k == 0 {
            "unbounded".into()
        } else {
            format!("K={k}")
        };
        LadderEntry::new(
            "analytic",
            setting,
            MethodOptions::Analytic(AnalyticOptions {
                intervals: k,
                ..Default::default()
            }),
        )
    }

    fn accum(times: u32) -> LadderEntry {
        LadderEntry::new(
            "accum",
            format!("{times} times"),
            MethodOptions::Accum(AccumOptions {
                times: Some(times),
                ..Default::default()
            }),
        )
    }

    fn stochastic(spp: u32) -> LadderEntry {
        LadderEntry::new(
            "stochastic/fallback",
            format!("{spp} spp"),
            MethodOptions::Stochastic(StochasticOptions {
                spp: Some(spp),
                ..Default::default()
            }),
        )
    }

    fn point(label: &str, ms: f64, psnr: f64) -> Point {
        Point {
            label: label.into(),
            seconds: ms * 1e-3,
            psnr,
        }
    }

    #[test]
    fn dominated_by_the_fastest_analytic_run_that_matches() {
        let records = [
            done(1, analytic(4), 30.0, 46.0),
            done(2, analytic(8), 40.0, 55.0),
            done(3, analytic(0), 60.0, 85.0),
            done(4, accum(16), 50.0, 49.7),
        ];
        let c = check(&records, DEFAULT_PSNR_FLOOR);
        assert_eq!(c.rows.len(), 1);
        // K=4 is faster but less accurate; K=8 and unbounded both dominate, K=8 is faster.
        assert_eq!(
            c.rows[0].verdict,
            Verdict::Dominated(point("analytic K=8", 40.0, 55.0))
        );
        assert!(c.holds());
        assert_eq!(c.analytic_runs, 3);
    }

    #[test]
    fn not_dominated_names_the_fastest_analytic_run_at_its_psnr() {
        let records = [
            done(1, analytic(4), 122.0, 46.1),
            done(2, analytic(0), 147.0, 85.9),
            done(3, accum(4), 10.0, 38.0),
            done(4, accum(16), 35.0, 49.7),
            done(5, stochastic(256), 2000.0, 60.0),
        ];
        let c = check(&records, DEFAULT_PSNR_FLOOR);
        assert_eq!(c.below_floor, 1, "accum 4 times is below 40 dB");
        assert_eq!(c.rows.len(), 2);
        assert_eq!(c.rows[0].run, point("accum 16 times", 35.0, 49.7));
        match &c.rows[0].verdict {
            Verdict::NotDominated(Closest::Slower {
                analytic,
                time_ratio,
            }) => {
                assert_eq!(analytic, &point("analytic unbounded", 147.0, 85.9));
                assert!((time_ratio - 147.0 / 35.0).abs() < 1e-12);
            }
            other => panic!("expected a slower analytic run, got {other:?}"),
        }
        assert_eq!(
            c.rows[1].verdict,
            Verdict::Dominated(point("analytic unbounded", 147.0, 85.9))
        );
        assert_eq!(c.dominated(), 1);
        assert!(!c.holds());
    }

    #[test]
    fn ties_in_time_or_psnr_count_as_dominated() {
        let run = point("accum 16 times", 50.0, 49.7);
        // Equal time, higher PSNR; equal PSNR, lower time; both equal.
        for a in [
            point("analytic K=2", 50.0, 60.0),
            point("analytic K=2", 20.0, 49.7),
            point("analytic K=2", 50.0, 49.7),
        ] {
            assert_eq!(
                verdict(&run, std::slice::from_ref(&a)),
                Verdict::Dominated(a)
            );
        }
        // Among equally fast dominating runs the more accurate one is named.
        let pts = [
            point("analytic K=2", 30.0, 50.0),
            point("analytic K=4", 30.0, 52.0),
        ];
        assert_eq!(verdict(&run, &pts), Verdict::Dominated(pts[1].clone()));
        // A hair slower or a hair less accurate is not dominating.
        let slower = point("analytic K=2", 50.000001, 60.0);
        let worse = point("analytic K=4", 10.0, 49.699999);
        assert!(matches!(
            verdict(&run, &[slower, worse.clone()]),
            Verdict::NotDominated(Closest::Slower { .. })
        ));
        assert_eq!(
            verdict(&run, std::slice::from_ref(&worse)),
            Verdict::NotDominated(Closest::LessAccurate(worse))
        );
    }

    #[test]
    fn a_run_on_the_floor_is_checked() {
        let records = [
            done(1, accum(4), 10.0, 40.0),
            done(2, analytic(0), 5.0, 40.0),
        ];
        let c = check(&records, 40.0);
        assert_eq!(c.rows.len(), 1);
        assert_eq!(c.below_floor, 0);
        assert!(c.holds());
    }

    #[test]
    fn without_analytic_runs_nothing_is_dominated() {
        let records = [
            RunRecord {
                index: 1,
                entry: analytic(4),
                outcome: Outcome::Failed("out of memory".into()),
                image_file: None,
            },
            done(2, accum(16), 35.0, 49.7),
        ];
        let c = check(&records, DEFAULT_PSNR_FLOOR);
        assert_eq!(c.analytic_runs, 0);
        assert_eq!(
            c.rows[0].verdict,
            Verdict::NotDominated(Closest::NoAnalytic)
        );
        assert_eq!(
            c.not_rendered,
            [(
                "analytic K=4".to_string(),
                "failed: out of memory".to_string()
            )]
        );
        let md = markdown_section(&c);
        assert!(
            md.contains("| accum 16 times | 49.70 | 35.0 | no | no analytic run |"),
            "{md}"
        );
        assert!(md.contains("- analytic K=4: failed: out of memory"), "{md}");
    }

    #[test]
    fn skipped_methods_are_listed_once_and_not_checked() {
        let why = "transparency is not supported".to_string();
        let records = [
            done(1, analytic(0), 40.0, 80.0),
            RunRecord {
                index: 2,
                entry: stochastic(4),
                outcome: Outcome::Skipped(why.clone()),
                image_file: None,
            },
            done(3, accum(16), 35.0, 49.7),
        ];
        let c = check(&records, DEFAULT_PSNR_FLOOR);
        assert_eq!(c.rows.len(), 1, "only accum is checked");
        assert_eq!(
            c.not_rendered,
            [("stochastic/fallback".to_string(), format!("skipped: {why}"))]
        );
        assert!(matches!(
            c.rows[0].verdict,
            Verdict::NotDominated(Closest::Slower { .. })
        ));
    }

    #[test]
    fn infinite_psnr_is_matched_only_by_infinite_psnr() {
        let inf = f64::INFINITY;
        let run = point("accum 4 times", 5.0, inf);
        let finite = point("analytic K=4", 1.0, 120.0);
        let exact_slow = point("analytic unbounded", 6.0, inf);
        let exact_fast = point("analytic K=2", 4.0, inf);
        assert_eq!(
            verdict(&run, std::slice::from_ref(&finite)),
            Verdict::NotDominated(Closest::LessAccurate(finite.clone()))
        );
        match verdict(&run, &[finite.clone(), exact_slow.clone()]) {
            Verdict::NotDominated(Closest::Slower {
                analytic,
                time_ratio,
            }) => {
                assert_eq!(analytic, exact_slow);
                assert!((time_ratio - 1.2).abs() < 1e-12);
            }
            other => panic!("expected a slower exact run, got {other:?}"),
        }
        assert_eq!(
            verdict(&run, &[finite, exact_slow, exact_fast.clone()]),
            Verdict::Dominated(exact_fast)
        );
        // An infinite PSNR passes any floor and prints as inf.
        let records = [done(1, accum(4), 5.0, inf), done(2, analytic(2), 4.0, inf)];
        let c = check(&records, 1e6);
        assert!(c.holds() && c.rows.len() == 1);
        assert!(
            markdown_section(&c)
                .contains("| accum 4 times | inf | 5.00 | yes | analytic K=2: inf dB in 4.00 ms |")
        );
    }

    #[test]
    fn nan_psnr_reaches_no_floor_and_dominates_nothing() {
        let records = [
            done(1, analytic(2), 1.0, f64::NAN),
            done(2, accum(4), 5.0, f64::NAN),
            done(3, accum(16), 20.0, 50.0),
        ];
        let c = check(&records, DEFAULT_PSNR_FLOOR);
        assert_eq!(c.below_floor, 1);
        assert_eq!(c.rows.len(), 1);
        assert_eq!(
            c.rows[0].verdict,
            Verdict::NotDominated(Closest::NoAnalytic)
        );
    }

    #[test]
    fn no_run_at_the_floor_holds_vacuously_and_says_so() {
        let records = [
            done(1, accum(4), 10.0, 30.0),
            done(2, analytic(0), 50.0, 80.0),
        ];
        let c = check(&records, DEFAULT_PSNR_FLOOR);
        assert!(c.rows.is_empty() && c.holds());
        let md = markdown_section(&c);
        assert!(
            md.contains("0 of 0 yes; 1 run below 40.00 dB not checked; 1 analytic run."),
            "{md}"
        );
        assert!(!md.contains("| run |"), "no empty table: {md}");
    }
}
