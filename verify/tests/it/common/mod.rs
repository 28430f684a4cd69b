//! Code shared by verify's integration tests (`use crate::common;`; each
//! topic uses only part of it).
#![allow(dead_code)]

pub mod strategies;
