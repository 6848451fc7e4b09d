//! Tests of ch5.
