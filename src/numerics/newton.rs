//! Sparse Newton solver that follows stable equilibria: detects loss of positive definiteness of the tangent and moves to the next stable state by an energy-decreasing method.
