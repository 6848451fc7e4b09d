//! Load-controlled peeling of a thin film from a wavy substrate (chapter 6), Eqs. (6.9)-(6.31).
