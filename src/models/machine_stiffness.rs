//! Adhesive contact with machine stiffness (chapter 2): the variational model of section 2.2 for spherical and conical tips, Eqs. (2.28)-(2.49), and appendix A.
