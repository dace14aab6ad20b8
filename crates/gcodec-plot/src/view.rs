//! What the picture looks at: a plane seen from its positive infeed axis,
//! or a fixed isometric view.

use std::fmt;
use std::str::FromStr;

use gcodec_exec::event::Plane;

use crate::geometry::Point3;

/// The projection of the picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum View {
    /// A working plane seen from its positive infeed axis, its abscissa
    /// to the right and its ordinate up (`G17`: X right, Y up; `G18`: Z
    /// right, X up; `G19`: Y right, Z up), so that a `G2` arc in it is
    /// clockwise on the page.
    Plane(Plane),
    /// The south-west isometric view: seen from (−1, −1, 1), X to the
    /// right and up, Y to the left and up, Z up; scaled by √(3/2) so that
    /// a length along an axis is drawn true to the scale bar.
    Iso,
}

impl View {
    /// The page's horizontal and vertical coordinate (vertical up) of a
    /// point.
    pub fn project(self, p: Point3) -> (f64, f64) {
        match self {
            Self::Plane(plane) => {
                let (h, v, _) = plane.axes();
                (p[h], p[v])
            }
            Self::Iso => {
                // cos 30°, sin 30°.
                const COS: f64 = 0.866_025_403_784_438_6;
                const SIN: f64 = 0.5;
                ((p[0] - p[1]) * COS, p[2] + (p[0] + p[1]) * SIN)
            }
        }
    }

    /// The working plane the page shows, whose arcs are drawn as arcs.
    pub fn plane(self) -> Option<Plane> {
        match self {
            Self::Plane(plane) => Some(plane),
            Self::Iso => None,
        }
    }

    /// The command-line name: `xy`, `xz` (the `G18` plane: Z right, X
    /// up), `yz`, `iso`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Plane(Plane::G17) => "xy",
            Self::Plane(Plane::G18) => "xz",
            Self::Plane(Plane::G19) => "yz",
            Self::Iso => "iso",
        }
    }
}

impl fmt::Display for View {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is no view.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownView(pub String);

impl fmt::Display for UnknownView {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "`{}` is not a view: xy, xz, yz or iso", self.0)
    }
}

impl std::error::Error for UnknownView {}

impl FromStr for View {
    type Err = UnknownView;

    fn from_str(name: &str) -> Result<Self, Self::Err> {
        match name.to_ascii_lowercase().as_str() {
            "xy" => Ok(Self::Plane(Plane::G17)),
            "xz" => Ok(Self::Plane(Plane::G18)),
            "yz" => Ok(Self::Plane(Plane::G19)),
            "iso" => Ok(Self::Iso),
            _ => Err(UnknownView(name.to_owned())),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_view_is_read_back_from_its_name() {
        for view in [
            View::Plane(Plane::G17),
            View::Plane(Plane::G18),
            View::Plane(Plane::G19),
            View::Iso,
        ] {
            assert_eq!(view.name().parse::<View>(), Ok(view));
        }
        assert_eq!("XY".parse::<View>(), Ok(View::Plane(Plane::G17)));
        assert!("top".parse::<View>().is_err());
    }

    #[test]
    fn g18_is_seen_with_z_right_and_x_up() {
        assert_eq!(View::Plane(Plane::G18).project([1.0, 2.0, 3.0]), (3.0, 1.0));
    }

    #[test]
    fn iso_draws_lengths_along_the_axes_true() {
        for axis in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
            let (u, v) = View::Iso.project(axis);
            assert!((u.hypot(v) - 1.0).abs() < 1e-12, "{axis:?}");
        }
        // Seen from (-1, -1, 1): that direction is drawn as a point.
        let (u, v) = View::Iso.project([-1.0, -1.0, 1.0]);
        assert!(u.abs() < 1e-12 && v.abs() < 1e-12);
    }
}
