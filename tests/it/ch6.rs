//! Tests of ch6.
