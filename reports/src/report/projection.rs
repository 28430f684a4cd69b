//! The one view of every 3-D picture in the report (surface wireframes, the
//! QI space curves): an orthographic projection seen from azimuth 35°,
//! elevation 30°, so that all such pictures read alike. The studies hand
//! over points in world coordinates; projecting is the report's business.

/// Azimuth of the view, degrees (rotation about the z axis).
const AZIMUTH_DEG: f64 = 35.0;
/// Elevation of the view above the xy plane, degrees.
const ELEVATION_DEG: f64 = 30.0;

/// Label of the projected horizontal axis.
pub const X_LABEL: &str = "oblique view (azimuth 35°)";
/// Label of the projected vertical axis.
pub const Y_LABEL: &str = "height (elevation 30°)";

/// `(x, y, z) ↦ (x cos a − y sin a, (x sin a + y cos a) sin e + z cos e)`
/// with `a` the azimuth and `e` the elevation: rotate about z, then tilt.
pub fn project(p: [f64; 3]) -> (f64, f64) {
    let (a, e) = (AZIMUTH_DEG.to_radians(), ELEVATION_DEG.to_radians());
    let x = p[0] * a.cos() - p[1] * a.sin();
    let depth = p[0] * a.sin() + p[1] * a.cos();
    (x, depth * e.sin() + p[2] * e.cos())
}

#[cfg(test)]
mod tests {
    use super::project;

    #[test]
    fn the_view_is_a_rotation_then_a_tilt() {
        // The z axis projects onto the vertical, shortened by cos 30°.
        let (x, y) = project([0.0, 0.0, 2.0]);
        assert!(x.abs() < 1e-15 && (y - 3f64.sqrt()).abs() < 1e-15);
        // A unit vector in the plane keeps its length across the view
        // before the tilt: x² + depth² = 1, and depth shows as depth·sin 30°.
        let (x, y) = project([1.0, 0.0, 0.0]);
        let depth = y / 0.5;
        assert!((x * x + depth * depth - 1.0).abs() < 1e-15);
        assert!((x - 35f64.to_radians().cos()).abs() < 1e-15);
    }
}
