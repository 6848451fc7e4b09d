//! Tests of ch3.
