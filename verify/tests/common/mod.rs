//! Code shared by verify's integration tests (each test file includes it
//! with `mod common;` and uses only part of it).
#![allow(dead_code)]

pub mod strategies;
