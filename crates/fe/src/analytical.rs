//! analytical
