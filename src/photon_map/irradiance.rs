//! Precomputed irradiance for fast final gathering (Christensen 1999, "Faster Photon Map
//! Global Illumination", JGT 4(3)).
//!
//! Irradiance is estimated once at a subset of the global map's photons (on the side each photon
//! arrived from); a final-gather ray then reads the nearest precomputed point whose normal agrees
//! with the surface it hit, instead of running a k-nearest estimate of its own.

use super::estimate::Estimator;
use super::{KdPoint, KdTree, Neighbours};
use crate::spectrum::BandValues;
use crate::spectrum::MAX_BANDS;
use glam::DVec3;
use rayon::prelude::*;

/// Normals of a cache point and a query must agree to this cosine.
const MIN_NORMAL_COS: f64 = 0.9;

#[derive(Clone, Copy, Debug)]
struct CachePoint {
    pos: [f32; 3],
    normal: [f32; 3],
    index: u32,
}

impl KdPoint for CachePoint {
    fn position(&self) -> [f32; 3] {
        self.pos
    }
}

/// Irradiance per band at points of a global photon map.
pub struct IrradianceCache {
    origin: DVec3,
    tree: KdTree<CachePoint>,
    bands: usize,
    values: Vec<f32>,
    max_radius: f64,
}

impl IrradianceCache {
    /// Estimates irradiance at every `stride`-th photon of the estimator's map.
    pub fn build(est: &Estimator, stride: usize) -> IrradianceCache {
        let all: Vec<u32> = (0..Self::points(est.map.len(), stride) as u32).collect();
        Self::from_values(est, stride, Self::estimate(est, stride, &all))
    }

    /// How many cache points a map of `map_len` photons gets: one per `stride` photons.
    pub fn points(map_len: usize, stride: usize) -> usize {
        map_len.div_ceil(stride.max(1))
    }

    /// Bytes a cache of `points` points of `bands` bands holds once built (tree and values).
    pub fn bytes_for(points: usize, bands: usize) -> usize {
        KdTree::<CachePoint>::bytes_for(points) + points * bands * 4
    }

    /// Where cache point `point` sits: the position of photon `point × stride` and the normal on
    /// the side the photon arrived from.
    fn site(est: &Estimator, stride: usize, point: u32) -> (DVec3, DVec3) {
        let p = est.map.record(point * stride.max(1) as u32);
        let side = if p.dir.dot(p.normal) < 0.0 { p.normal } else { -p.normal };
        (p.position, side)
    }

    /// The irradiance at cache points `points` (indices below [`IrradianceCache::points`]): the
    /// estimator's band count of f32 values per point, in the order given. Any partition of the
    /// points, estimated anywhere and put back in point order, gives the values
    /// [`IrradianceCache::build`] computes.
    pub fn estimate(est: &Estimator, stride: usize, points: &[u32]) -> Vec<f32> {
        let bands = est.bands.count;
        // Written in place: 4 bytes per band and point, nothing larger held per point.
        let mut values = vec![0f32; points.len() * bands];
        if bands == 0 {
            return values;
        }
        values.par_chunks_mut(bands).zip(points.par_iter()).for_each_init(Neighbours::default, |nb, (out, &i)| {
            let (pos, side) = Self::site(est, stride, i);
            let e = est.irradiance(pos, side, nb);
            for (o, v) in out.iter_mut().zip(&e[..bands]) {
                *o = *v as f32;
            }
        });
        values
    }

    /// The cache from the values of every point in point order (as [`IrradianceCache::estimate`]
    /// returns them for all points).
    ///
    /// # Panics
    /// If `values` does not hold the band count of values for every point.
    pub fn from_values(est: &Estimator, stride: usize, values: Vec<f32>) -> IrradianceCache {
        let bands = est.bands.count;
        let n = Self::points(est.map.len(), stride);
        assert_eq!(values.len(), n * bands, "irradiance values: {n} points of {bands} bands expected");
        let sites: Vec<(DVec3, DVec3)> = (0..n as u32).into_par_iter().map(|i| Self::site(est, stride, i)).collect();
        let origin = sites.first().map_or(DVec3::ZERO, |c| c.0);
        let points: Vec<CachePoint> = sites
            .iter()
            .enumerate()
            .map(|(i, (pos, n))| CachePoint {
                pos: (*pos - origin).as_vec3().to_array(),
                normal: n.as_vec3().to_array(),
                index: i as u32,
            })
            .collect();
        IrradianceCache { origin, tree: KdTree::build(points), bands, values, max_radius: est.max_radius }
    }

    /// Number of points with precomputed irradiance.
    pub fn len(&self) -> usize {
        self.tree.len()
    }

    /// True when no point has precomputed irradiance.
    pub fn is_empty(&self) -> bool {
        self.tree.is_empty()
    }

    /// Bytes held by the cache.
    pub fn memory_bytes(&self) -> usize {
        self.tree.len() * std::mem::size_of::<CachePoint>() + self.values.len() * 4
    }

    /// Irradiance per band at the nearest cache point within the map's maximum radius whose
    /// normal agrees with `n`; `None` if there is none.
    pub fn lookup(&self, x: DVec3, n: DVec3, nb: &mut Neighbours) -> Option<BandValues> {
        let q = (x - self.origin).as_vec3().to_array();
        self.tree.knn(q, 8, (self.max_radius * self.max_radius) as f32, nb);
        let items = self.tree.items();
        let best = nb
            .items
            .iter()
            .filter(|(i, _)| {
                let c = items[*i as usize].normal;
                DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64).dot(n) >= MIN_NORMAL_COS
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        let start = items[best.0 as usize].index as usize * self.bands;
        let mut out = [0.0; MAX_BANDS];
        for (o, v) in out.iter_mut().zip(&self.values[start..start + self.bands]) {
            *o = *v as f64;
        }
        Some(out)
    }
}
