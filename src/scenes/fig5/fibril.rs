//! Fig. 5.2b: the stiffness of a tilted fibril (section 5.2).

use crate::error::{Error, Result};
use crate::figure::{Axis, Figure, Panel, Series, Style};
use crate::job::Job;
use crate::models::fibril::tilted_fibril_stiffness;
use crate::numerics::curve::linspace;
use crate::params::Range;
use crate::scenes::{Scene, SceneHeader};

crate::scene_params! {
    /// Parameters of scene fig5.2b (section 5.4.1).
    pub struct Fig5_2bParams {
        /// Radius-to-length ratio R_f/l_f of the fibril (below 0.8: the half-stiffness angle exists).
        radius_over_length: f64 = 0.1, unit = "", range = Range::open(0.0, 0.8);
        /// Points on the curve.
        points: usize = 181, unit = "", range = Range::between(3.0, 1.0e5);
    }
}

crate::scene! {
    /// Fig. 5.2b: stiffness of a tilted fibril against the tilt angle, Eq. (5.11).
    pub struct Fig5_2b {
        id: "fig5.2b",
        chapter: "5",
        params: Fig5_2bParams,
        title: "Stiffness of a tilted fibril",
        caption: "Stiffness k_f of a fibril tilted at angle theta to its backing, Eq. (5.11), \
            in units of the axial stiffness pi R_f^2 E/l_f, for R_f/l_f = 1/10: pure bending at theta = 0, \
            pure compression (stiffest) at theta = pi/2.",
        results: &[
            ("bending_stiffness_norm", "k_f(0) / (pi R_f^2 E / l_f) = 3 R_f^2 / (4 l_f^2)"),
            ("compression_stiffness_norm", "k_f(pi/2) / (pi R_f^2 E / l_f) = 1"),
            ("half_stiffness_angle_deg", "angle where k_f is half the axial stiffness"),
        ],
    }
}

impl Scene for Fig5_2b {
    fn quick(p: &mut Self::Params) {
        p.points = p.points.min(31);
    }

    fn run(p: &Self::Params, job: &Job) -> Result<Figure> {
        let r = p.radius_over_length;
        let axial = std::f64::consts::PI * r * r;
        let norm = |theta: f64| Ok::<f64, Error>(tilted_fibril_stiffness(1.0, r, 1.0, theta)? / axial);
        let mut pts = Vec::with_capacity(p.points);
        for t in linspace(0.0, std::f64::consts::FRAC_PI_2, p.points) {
            pts.push((t.to_degrees(), norm(t)?));
        }
        job.check()?;
        let mut panel = Panel::new(
            Axis::linear("Tilt angle θ", "deg"),
            Axis::linear("Stiffness k_f l_f/(π R_f² E)", ""),
        )
        .titled("(b)", format!("R_f/l_f = {r}"));
        panel.add(Series::new("k_f, Eq. (5.11)", Style::Stable, pts).with_color(0));
        let mut fig = Figure::new(Self::ID, Self::TITLE).with_panel(panel);
        fig.result("bending_stiffness_norm", norm(0.0)?);
        fig.result("compression_stiffness_norm", norm(std::f64::consts::FRAC_PI_2)?);
        let half = crate::numerics::roots::brent(
            |t| norm(t).unwrap_or(f64::NAN) - 0.5,
            0.0,
            std::f64::consts::FRAC_PI_2,
            1e-13,
        )?;
        fig.result("half_stiffness_angle_deg", half.to_degrees());
        job.progress(1.0, "done");
        Ok(fig)
    }
}
