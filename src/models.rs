//! Physical models, one module per theory. Models know equations only: no printing, no files, no
//! front-end types. Every public function names the equation it implements.

pub mod axisymmetric;
pub mod body_force_fe;
pub mod classical;
pub mod ddh;
pub mod fibril;
pub mod fuller_tabor;
pub mod lennard_jones;
pub mod machine_stiffness;
pub mod maugis_dugdale;
pub mod peeling;
pub mod spring_array;
pub mod wavy_jkr;
