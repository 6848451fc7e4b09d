//! Tests of ch2.
