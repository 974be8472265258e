//! Longitude and latitude in, metres inside: a local azimuthal equidistant projection on
//! the sphere about the centre of the data, and its inverse for the outputs.

use crate::error::Error;
use crate::geom::{Aabb, Point};

/// The sphere's radius in metres (the mean Earth radius of IUGG, 6371008.8 m).
pub const EARTH_RADIUS_M: f64 = 6_371_008.8;

/// How a reader takes the coordinates of a file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Projection {
    /// As they are, planar.
    #[default]
    None,
    /// As longitude and latitude in degrees (GeoJSON only), projected to metres by the
    /// [`LocalProjection`] about the centre of the data's bounding box.
    Local,
}

/// The azimuthal equidistant projection on the sphere of radius [`EARTH_RADIUS_M`] about
/// `(lon0, lat0)` (degrees): a point goes to the plane at its great-circle distance from
/// the centre, in its direction (east `x`, north `y`), in metres. Distances from the
/// centre are exact; others are within a factor `c / sin c` (`c` the angle from the
/// centre), 1.0004 at 2° (220 km) and 1.04 at 20°.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalProjection {
    /// The centre's longitude in degrees.
    pub lon0: f64,
    /// The centre's latitude in degrees.
    pub lat0: f64,
}

impl LocalProjection {
    /// The projection about the centre of the bounding box of `lon_lat` (`x` longitude,
    /// `y` latitude, degrees). Refuses what it does not handle: no point, a coordinate
    /// out of range, data spanning more than 180° of longitude (the antimeridian is not
    /// handled) or reaching a pole.
    pub fn about(lon_lat: &Aabb) -> Result<LocalProjection, Error> {
        let refuse = |m: String| Err(Error::scene("coordinates", m));
        let [lon_min, lat_min, lon_max, lat_max] = lon_lat.to_array();
        if !(-180.0..=180.0).contains(&lon_min) || !(-180.0..=180.0).contains(&lon_max) {
            return refuse(format!(
                "longitudes from {lon_min} to {lon_max}: longitude and latitude in degrees need longitudes in [-180, 180]"
            ));
        }
        if !(lat_min > -90.0 && lat_max < 90.0) {
            return refuse(format!(
                "latitudes from {lat_min} to {lat_max}: the local projection needs data away from the poles, latitudes in (-90, 90)"
            ));
        }
        if lon_max - lon_min > 180.0 {
            return refuse(format!(
                "longitudes from {lon_min} to {lon_max} span more than 180°: the local projection does not handle such data (nor data across the antimeridian)"
            ));
        }
        Ok(LocalProjection {
            lon0: 0.5 * (lon_min + lon_max),
            lat0: 0.5 * (lat_min + lat_max),
        })
    }

    /// The point `(lon, lat)` (degrees) in metres.
    pub fn forward(&self, lon_lat: Point) -> Point {
        let (sp0, cp0) = self.lat0.to_radians().sin_cos();
        let (sp, cp) = lon_lat.y.to_radians().sin_cos();
        let (sl, cl) = (lon_lat.x - self.lon0).to_radians().sin_cos();
        // the direction (east, north) scaled by sin c, and cos c
        let (e, n) = (cp * sl, cp0 * sp - sp0 * cp * cl);
        let cos_c = sp0 * sp + cp0 * cp * cl;
        let sin_c = e.hypot(n);
        if sin_c == 0.0 {
            return Point::new(0.0, 0.0);
        }
        let k = EARTH_RADIUS_M * sin_c.atan2(cos_c) / sin_c;
        Point::new(k * e, k * n)
    }

    /// The point `xy` (metres) back in longitude and latitude (degrees).
    pub fn inverse(&self, xy: Point) -> Point {
        let rho = xy.x.hypot(xy.y);
        if rho == 0.0 {
            return Point::new(self.lon0, self.lat0);
        }
        let (sp0, cp0) = self.lat0.to_radians().sin_cos();
        let (sc, cc) = (rho / EARTH_RADIUS_M).sin_cos();
        let lat = (cc * sp0 + xy.y * sc * cp0 / rho).clamp(-1.0, 1.0).asin();
        let dlon = (xy.x * sc).atan2(rho * cp0 * cc - xy.y * sp0 * sc);
        Point::new(self.lon0 + dlon.to_degrees(), lat.to_degrees())
    }

    /// The bounding box in metres of the box `lon_lat` (degrees): of its outline's
    /// projection, 64 points a side, grown by a thousandth so that it holds the whole
    /// projected box.
    pub fn forward_box(&self, lon_lat: &Aabb) -> Aabb {
        let [x0, y0, x1, y1] = lon_lat.to_array();
        let mut lo = Point::new(f64::INFINITY, f64::INFINITY);
        let mut hi = Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
        for k in 0..=64 {
            let t = k as f64 / 64.0;
            let (x, y) = (x0 + t * (x1 - x0), y0 + t * (y1 - y0));
            for p in [(x, y0), (x, y1), (x0, y), (x1, y)] {
                let q = self.forward(Point::new(p.0, p.1));
                lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
                hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
            }
        }
        let m = (hi - lo) * 1e-3;
        Aabb::new(lo - m, hi + m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The great-circle distance in metres between two (lon, lat) points in degrees.
    fn haversine(a: Point, b: Point) -> f64 {
        let (p1, p2) = (a.y.to_radians(), b.y.to_radians());
        let dp = p2 - p1;
        let dl = (b.x - a.x).to_radians();
        let h = (dp / 2.0).sin().powi(2) + p1.cos() * p2.cos() * (dl / 2.0).sin().powi(2);
        2.0 * EARTH_RADIUS_M * h.sqrt().asin()
    }

    fn samples() -> Vec<Point> {
        let mut out = Vec::new();
        for i in 0..=20 {
            for j in 0..=20 {
                out.push(Point::new(-30.0 + 3.0 * i as f64, 20.0 + 2.5 * j as f64));
            }
        }
        out
    }

    #[test]
    fn the_inverse_undoes_the_projection() {
        for centre in [(0.0, 0.0), (-1.5, 51.5), (151.2, -33.9), (2.0, 45.0)] {
            let p = LocalProjection {
                lon0: centre.0,
                lat0: centre.1,
            };
            for q in samples() {
                let q = Point::new(q.x + p.lon0, q.y - 45.0 + p.lat0);
                if q.y.abs() >= 90.0 {
                    continue;
                }
                let back = p.inverse(p.forward(q));
                assert!(
                    (back.x - q.x).abs() < 1e-9 && (back.y - q.y).abs() < 1e-9,
                    "{q:?} came back as {back:?} about {centre:?}"
                );
            }
            let c = Point::new(p.lon0, p.lat0);
            assert_eq!(p.inverse(p.forward(c)), c);
        }
    }

    #[test]
    fn distances_from_the_centre_are_great_circle_distances() {
        let p = LocalProjection {
            lon0: 4.9,
            lat0: 52.4,
        };
        let c = Point::new(p.lon0, p.lat0);
        for q in samples() {
            let d = p.forward(q);
            let rho = d.x.hypot(d.y);
            let h = haversine(c, q);
            // both are R·c in f64: agreement to a few ulps of the distance
            assert!((rho - h).abs() <= 1e-9 * h.max(1.0), "{q:?}: {rho} vs {h}");
        }
        // east is +x, north is +y
        let east = p.forward(Point::new(5.0, 52.4));
        let north = p.forward(Point::new(4.9, 52.5));
        assert!(east.x > 0.0 && north.y > 0.0 && north.x.abs() < 1e-9);
    }

    #[test]
    fn refuses_the_poles_wide_data_and_out_of_range_coordinates() {
        let about = |a: [f64; 4]| LocalProjection::about(&Aabb::from_array(a));
        let p = about([-10.0, 40.0, 20.0, 60.0]).unwrap();
        assert_eq!((p.lon0, p.lat0), (5.0, 50.0));
        for bad in [
            [-100.0, 0.0, 100.0, 10.0],
            [0.0, 80.0, 10.0, 90.0],
            [0.0, -90.0, 10.0, 0.0],
            [170.0, 0.0, 190.0, 10.0],
        ] {
            let e = about(bad).unwrap_err().to_string();
            assert!(e.contains("coordinates"), "{bad:?}: {e}");
        }
    }
}
