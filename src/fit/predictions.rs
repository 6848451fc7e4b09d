//! The predictions of the machine-stiffness model and of JKR for one AFM experiment with a
//! spherical tip (Sec. 2.4): the instabilities in SI units and the P-h panel of both models.
//! Used by the fit of measured curves and by the scenes of Fig. 2.8, which both sit above it.

use crate::error::Result;
use crate::figure::{Axis, Marker, MarkerShape, Panel, Series, Style};
use crate::models::machine_stiffness::{Experiment, MachineStiffness, TipShape};
use crate::numerics::curve::linspace;

/// Predictions of both models for one experiment, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Predictions {
    /// Machine-stiffness pull-in (SI).
    pub pull_in: crate::models::machine_stiffness::Instability,
    /// Machine-stiffness pull-off (SI).
    pub pull_off: crate::models::machine_stiffness::Instability,
    /// JKR pull-in force (at h = 0) [N].
    pub jkr_pull_in_force: f64,
    /// JKR pull-off force, −5πwR/6 [N].
    pub jkr_pull_off_force: f64,
    /// JKR pull-off depth h_D [m].
    pub jkr_pull_off_depth: f64,
}

/// The predictions of both models for an experiment with a spherical tip (Sec. 2.4).
///
/// # Errors
/// Model errors (invalid parameters).
pub fn predictions(x: &Experiment) -> Result<Predictions> {
    let jkr = jkr_predictions(x)?;
    let (pull_in, pull_off) = x.instabilities()?;
    Ok(Predictions {
        pull_in,
        pull_off,
        jkr_pull_in_force: jkr.pull_in_force,
        jkr_pull_off_force: jkr.pull_off_force,
        jkr_pull_off_depth: jkr.pull_off_depth,
    })
}

/// The JKR instabilities of a spherical tip under depth control (Sec. 2.3), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JkrPredictions {
    /// Pull-in force (at h = 0) [N].
    pub pull_in_force: f64,
    /// Pull-off force, −5πwR/6 [N].
    pub pull_off_force: f64,
    /// Pull-off depth h_D [m].
    pub pull_off_depth: f64,
}

/// The JKR predictions of an experiment with a spherical tip, in closed form on the branch
/// (1.2) (no search over the machine's folds: [`predictions`] adds those).
///
/// # Errors
/// Model errors (invalid parameters).
pub fn jkr_predictions(x: &Experiment) -> Result<JkrPredictions> {
    let sc = x.scales();
    let stiff = MachineStiffness::new(TipShape::Sphere, 1.0)?;
    let a_d = crate::models::machine_stiffness::sphere_depth_minimum_radius();
    // JKR pull-in at h = 0: ā³/² = 4/3 on h̄ = ā² − (4/3)√ā = 0.
    let a_b = (4.0f64 / 3.0).powf(2.0 / 3.0);
    Ok(JkrPredictions {
        pull_in_force: sc.force * stiff.branch_force(a_b),
        pull_off_force: sc.force * stiff.branch_force(a_d),
        pull_off_depth: sc.h * stiff.depth(a_d),
    })
}

/// A P-h panel of both models for one experiment, in nm and nN, with the pull-off squares.
///
/// # Errors
/// Model errors.
pub fn ph_panel(
    x: &Experiment,
    label: &str,
    title: &str,
    max_depth_norm: f64,
    points: usize,
) -> Result<Panel> {
    let sc = x.scales();
    let pr = predictions(x)?;
    let m = x.model()?;
    let (nm, nn) = (1e9, 1e9);
    let a_d = crate::models::machine_stiffness::sphere_depth_minimum_radius();
    let a_top = crate::models::machine_stiffness::sphere_radius_at_depth(max_depth_norm);
    let pt = |a: f64| (m.depth(a) * sc.h * nm, m.branch_force(a) * sc.force * nn);
    let mut panel = Panel::new(
        Axis::linear("Indentation depth h", "nm"),
        Axis::linear("Contact force P", "nN"),
    )
    .titled(label, title);
    // Machine-stiffness model: stable from the pull-off radius up; jumps at pull-in and pull-off.
    let a_o = pr.pull_off.before.a / sc.a;
    let a_i = pr.pull_in.after.a / sc.a;
    panel.add(
        Series::new(
            "machine stiffness (2.31b)-(2.32b)",
            Style::Stable,
            linspace(a_o, a_top.max(a_i), points)
                .into_iter()
                .map(pt)
                .collect(),
        )
        .with_color(0),
    );
    let jump = |i: &crate::models::machine_stiffness::Instability| {
        vec![
            (i.before.h * nm, i.before.force * nn),
            (i.after.h * nm, i.after.force * nn),
        ]
    };
    panel.add(
        Series::new("pull-in", Style::Jump, jump(&pr.pull_in))
            .with_color(0)
            .without_legend(),
    );
    panel.add(
        Series::new("pull-off", Style::Jump, jump(&pr.pull_off))
            .with_color(0)
            .without_legend(),
    );
    // JKR (1.2): stable from ā_D; pull-in at h = 0, pull-off at h_D, no depth change.
    panel.add(
        Series::new(
            "JKR (1.2)",
            Style::Stable,
            linspace(a_d, a_top.max(a_i), points)
                .into_iter()
                .map(pt)
                .collect(),
        )
        .with_color(1),
    );
    panel.add(
        Series::new(
            "JKR pull-in",
            Style::Jump,
            vec![(0.0, 0.0), (0.0, pr.jkr_pull_in_force * nn)],
        )
        .with_color(1)
        .without_legend(),
    );
    panel.add(
        Series::new(
            "JKR pull-off",
            Style::Jump,
            vec![
                (pr.jkr_pull_off_depth * nm, pr.jkr_pull_off_force * nn),
                (pr.jkr_pull_off_depth * nm, 0.0),
            ],
        )
        .with_color(1)
        .without_legend(),
    );
    panel.mark(
        Marker::new(
            "pull-off (machine stiffness)",
            MarkerShape::PullOff,
            pr.pull_off.before.h * nm,
            pr.pull_off.before.force * nn,
        )
        .with_color(0),
    );
    panel.mark(
        Marker::new(
            "pull-off (JKR)",
            MarkerShape::PullOff,
            pr.jkr_pull_off_depth * nm,
            pr.jkr_pull_off_force * nn,
        )
        .with_color(1),
    );
    Ok(panel)
}
