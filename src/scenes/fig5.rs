//! Chapter 5 scenes: fibril stiffness (Fig. 5.2b), the single-spring model (Figs. 5.3-5.5),
//! and the spring arrays on random rough surfaces (Figs. 5.7-5.11).

mod arrays;
mod coupled;
mod efficiency;
mod ensemble;
mod fibril;
mod single_spring;

use super::sweep::Swept;
use super::{Registered, SceneDyn};

pub use arrays::{Fig5_7, Fig5_7Params};
pub use coupled::{CouplingParams, Fig5_10, Fig5_10Accuracy, Fig5_10AccuracyParams, Fig5_11};
pub use efficiency::{Fig5_8, Fig5_8Params, Fig5_9, Fig5_9Params};
pub use fibril::{Fig5_2b, Fig5_2bParams};
pub use single_spring::{Fig5_3, Fig5_3Params, Fig5_4, Fig5_4Params, Fig5_5, Fig5_5Params};

/// The scenes of this chapter, in figure order.
pub const SCENES: &[&dyn SceneDyn] = &[
    &Registered::<Fig5_2b>::NEW,
    &Registered::<Fig5_3>::NEW,
    &Registered::<Fig5_4>::NEW,
    &Registered::<Fig5_5>::NEW,
    &Registered::<Fig5_7>::NEW,
    &Swept::<Fig5_8>::NEW,
    &Swept::<Fig5_9>::NEW,
    &Registered::<Fig5_10>::NEW,
    &Registered::<Fig5_11>::NEW,
    &Registered::<Fig5_10Accuracy>::NEW,
];
