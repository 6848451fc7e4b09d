//! The multiple-spring model of section 5.5 on a random rough surface, Eqs. (5.31)-(5.36).
