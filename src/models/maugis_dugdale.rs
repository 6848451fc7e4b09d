//! The Maugis-Dugdale model, Eq. (3.3), traced through its turning points, and the energy loss per asperity, Eqs. (3.4)-(3.6).
