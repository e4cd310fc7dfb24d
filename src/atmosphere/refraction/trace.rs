//! The ray from the observer out of the atmosphere (see the module notes of
//! [`super`]): one Dormand–Prince step at a time, watching for the top, the ground and turning
//! points. Steps end on the spheres where ∇n is not smooth (the profile's layer boundaries, the
//! taper's start and the top; [`KinkSpheres`]): a step straddling a jump of ∇n can pass the
//! error test with ~100 times the tolerated error (tests/refraction.rs), which made the traced
//! refraction depend on where the step-size rule happened to put the step ends (issue 18).

use crate::atmosphere::{Atmosphere, Earth};
use crate::error::{Error, Result};
use crate::ode::kink::KinkSpheres;
use crate::ode::{Integrator, Method, OdeState, RayY, Step};
use glam::DVec3;

/// Tolerances and limits of the tracer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Relative tolerance of the Dormand–Prince error norm.
    pub rtol: f64,
    /// Absolute tolerance (m for positions, dimensionless for the ray vector).
    pub atol: f64,
    /// A ray still inside the atmosphere after this path length is trapped, m.
    pub max_path_m: f64,
}

impl Default for Settings {
    /// rtol = atol = 10⁻¹² (the refraction then changes by less than 10⁻³″ when they are
    /// tightened further; tests/refraction.rs), and 20 000 km: half-way round the Earth.
    fn default() -> Settings {
        Settings { rtol: 1e-12, atol: 1e-12, max_path_m: 2e7 }
    }
}

/// How a traced ray ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outcome {
    /// Left through the top; the star is at this true altitude, rad.
    Escaped {
        /// True altitude of the star, rad.
        true_altitude_rad: f64,
    },
    /// Went into the ground without ever turning down (a ray aimed below the horizon); the
    /// distance along the ground (at radius R) from the observer's foot, m.
    Ground {
        /// Distance along the ground (at radius R) from the observer's foot, m.
        distance_m: f64,
    },
    /// Turned from climbing to descending inside the atmosphere (ducting) and did not escape:
    /// its highest point, and where it met the ground (`None`: still aloft after
    /// [`Settings::max_path_m`]).
    Trapped {
        /// Highest point of the path above the ground, m.
        max_height_m: f64,
        /// Distance along the ground (at radius R) from the observer's foot to where it landed, m;
        /// `None`: still aloft.
        ground_distance_m: Option<f64>,
    },
}

/// One traced ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trace {
    /// Apparent altitude at the observer (elevation of the launch direction above the
    /// horizontal), rad.
    pub apparent_altitude_rad: f64,
    /// How the ray ended.
    pub outcome: Outcome,
    /// Arc length from the observer to where the trace ended, m.
    pub path_length_m: f64,
    /// Accepted integrator steps.
    pub ode_steps: u64,
    /// Rejected integrator steps.
    pub ode_rejected: u64,
}

impl Trace {
    /// The true altitude of the star, when the ray escaped.
    pub fn true_altitude_rad(&self) -> Option<f64> {
        match self.outcome {
            Outcome::Escaped { true_altitude_rad } => Some(true_altitude_rad),
            _ => None,
        }
    }

    /// Refraction R = apparent − true altitude, rad, when the ray escaped.
    pub fn refraction_rad(&self) -> Option<f64> {
        self.true_altitude_rad().map(|t| self.apparent_altitude_rad - t)
    }
}

/// Traces rays from one observer through one atmosphere at one wavelength.
#[derive(Clone, Debug)]
pub struct Tracer<'a> {
    atmosphere: &'a Atmosphere,
    wavelength_nm: f64,
    centre: DVec3,
    radius_m: f64,
    observer: DVec3,
    /// The observer's vertical û and the horizontal direction the rays are aimed along.
    up: DVec3,
    horizontal: DVec3,
    settings: Settings,
    /// The spheres where ∇n is not smooth (USA76's layer boundaries, the start and the end of
    /// the taper at the top), where steps end ([`KinkSpheres`]).
    kinks: KinkSpheres,
}

/// A kink crossing closer than this is the one the path is on, m (as for scene paths).
const KINK_MIN_M: f64 = 1e-6;

impl<'a> Tracer<'a> {
    /// An observer `observer_height_m` (0 ≤ h₀ < top) above the ground of `atmosphere`, which
    /// must sit on a spherical Earth, looking at `wavelength_nm`.
    pub fn new(
        atmosphere: &'a Atmosphere,
        wavelength_nm: f64,
        observer_height_m: f64,
        settings: Settings,
    ) -> Result<Tracer<'a>> {
        let Earth::Spherical(sphere) = atmosphere.earth else {
            return Err(Error::input(
                None,
                format!(
                    "atmosphere \"{}\" has a flat Earth; astronomical refraction needs earth = \"spherical\"",
                    atmosphere.name
                ),
            ));
        };
        check_inputs(atmosphere, wavelength_nm, observer_height_m, &settings)?;
        let up = (-sphere.centre).try_normalize().unwrap_or(DVec3::Y);
        let horizontal = (DVec3::X - up * up.x).try_normalize().unwrap_or_else(|| up.any_orthonormal_vector());
        // The top too: there n − 1 tapers to 0 with zero slope but not zero curvature, and the
        // trace ends on the first step past it.
        let heights = atmosphere.kink_heights_m().into_iter().chain([atmosphere.top_m()]);
        let radii: Vec<f64> = heights.map(|h| sphere.radius_m + h).collect();
        let sample = |p: DVec3| atmosphere.n_grad(wavelength_nm, p);
        let kinks = KinkSpheres::new(&sample, sphere.centre, &radii);
        Ok(Tracer {
            atmosphere,
            wavelength_nm,
            centre: sphere.centre,
            radius_m: sphere.radius_m,
            observer: sphere.centre + (sphere.radius_m + observer_height_m) * up,
            up,
            horizontal,
            settings,
            kinks,
        })
    }

    /// The atmosphere traced through.
    pub fn atmosphere(&self) -> &'a Atmosphere {
        self.atmosphere
    }

    /// The wavelength traced, nm.
    pub fn wavelength_nm(&self) -> f64 {
        self.wavelength_nm
    }

    /// The observer's position in the scene frame.
    pub fn observer(&self) -> DVec3 {
        self.observer
    }

    /// The same observer at another wavelength.
    pub fn at_wavelength(&self, wavelength_nm: f64) -> Result<Tracer<'a>> {
        check_wavelength(self.atmosphere, wavelength_nm)?;
        Ok(Tracer { wavelength_nm, ..self.clone() })
    }

    /// The refraction at apparent altitude `apparent_altitude_rad`, rad (`None` when the ray
    /// does not escape).
    pub fn refraction_rad(&self, apparent_altitude_rad: f64) -> Result<Option<f64>> {
        Ok(self.trace(apparent_altitude_rad)?.refraction_rad())
    }

    /// Traces the ray leaving the observer at `apparent_altitude_rad` (−π/2 … π/2).
    pub fn trace(&self, apparent_altitude_rad: f64) -> Result<Trace> {
        let a = apparent_altitude_rad;
        if !(a.is_finite() && a.abs() <= std::f64::consts::FRAC_PI_2) {
            return Err(Error::input(
                None,
                format!("apparent altitude {} deg is out of range; expected −90 … 90 deg", a.to_degrees()),
            ));
        }
        let field = |p: DVec3| self.atmosphere.n_grad(self.wavelength_nm, p);
        let dir = self.horizontal * a.cos() + self.up * a.sin();
        let mut state = OdeState::launch(&field, self.observer, dir)?;
        let s = &self.settings;
        let mut ode = Integrator::new(method(s))?;
        let mut climb = Climb::new(self.height(state.y.r), self.radial(&state.y));
        // ∇n where the next step starts (the first step's slope, sampled once): the path's
        // curvature, which predicts where it meets a kink.
        let mut grad = ode.prime(&field, &state.y)?.v;
        let outcome = loop {
            let left = s.max_path_m - state.s;
            if left <= 0.0 {
                break Outcome::Trapped { max_height_m: climb.max_height_m, ground_distance_m: None };
            }
            let tol_v = method(s).kink_tolerance(state.y.v.length());
            let cut = self.kinks.next_cut(state.y.r, state.y.direction(), state.y.curvature(grad), KINK_MIN_M, tol_v);
            let step = ode.step(&field, &mut state, cut.map_or(left, |t| t.min(left)))?;
            grad = step.dense.f1.v;
            if let Some(theta) = self.ground_crossing(&step) {
                let hit = step.state_at(theta);
                state = hit;
                climb.observe(self, &step, theta);
                break climb.ground_outcome(self.ground_distance(hit.y.r));
            }
            climb.observe(self, &step, 1.0);
            if self.height(state.y.r) >= self.atmosphere.top_m() {
                break Outcome::Escaped { true_altitude_rad: self.altitude_of(state.y.v) };
            }
        };
        let c = ode.counters();
        Ok(Trace {
            apparent_altitude_rad: a,
            outcome,
            path_length_m: state.s,
            ode_steps: c.accepted,
            ode_rejected: c.rejected,
        })
    }

    /// Height above the ground, m.
    fn height(&self, p: DVec3) -> f64 {
        self.atmosphere.earth.height(p)
    }

    /// The rate of climb dh/ds ∝ v·∇h (its sign is what matters).
    fn radial(&self, y: &RayY) -> f64 {
        y.v.dot(self.atmosphere.earth.height_grad(y.r).1)
    }

    /// The angle of direction `v` above the observer's horizontal plane.
    fn altitude_of(&self, v: DVec3) -> f64 {
        let d = v.normalize_or_zero();
        let s = d.dot(self.up);
        s.atan2((d - s * self.up).length())
    }

    /// The distance along the ground from the observer's foot to below `p`, m.
    fn ground_distance(&self, p: DVec3) -> f64 {
        let (a, b) = (self.observer - self.centre, p - self.centre);
        self.radius_m * a.cross(b).length().atan2(a.dot(b))
    }

    /// The step fraction at which the path first goes below the ground, if it does on `step`:
    /// at its end, or — when the step passes a lowest point (dh/ds from < 0 to > 0) — at that
    /// point, so a dip below the ground inside one step is not missed.
    fn ground_crossing(&self, step: &Step) -> Option<f64> {
        let h = |t: f64| self.height(step.position_at(t));
        if h(1.0) < 0.0 {
            return Some(first_below(&h, 0.0, 1.0));
        }
        if self.radial(&step.y0()) < 0.0 && self.radial(&step.y1()) > 0.0 {
            let t = extremum(&h, false);
            if h(t) < 0.0 {
                return Some(first_below(&h, 0.0, t));
            }
        }
        None
    }
}

/// What the path's height has done so far: its highest point and whether it has turned down.
struct Climb {
    max_height_m: f64,
    /// dh/ds ≥ 0 somewhere so far (at the start or at a step's end).
    rose: bool,
    /// Descending after having risen: a turning point inside the atmosphere.
    turned_down: bool,
}

impl Climb {
    fn new(h0: f64, radial0: f64) -> Climb {
        Climb { max_height_m: h0, rose: radial0 >= 0.0, turned_down: false }
    }

    /// Takes in the part of `step` up to fraction `upto` (its end, or a ground crossing).
    fn observe(&mut self, tracer: &Tracer, step: &Step, upto: f64) {
        let h = |t: f64| tracer.height(step.position_at(t * upto));
        let (r0, r1) = (tracer.radial(&step.y0()), tracer.radial(&step.state_at(upto).y));
        let top = if r0 > 0.0 && r1 < 0.0 { h(extremum(&h, true)) } else { h(1.0) };
        self.max_height_m = self.max_height_m.max(top).max(h(0.0));
        if r1 < 0.0 && (self.rose || r0 > 0.0) {
            self.turned_down = true;
        }
        self.rose |= r1 >= 0.0;
    }

    /// The outcome of meeting the ground `distance_m` from the observer.
    fn ground_outcome(&self, distance_m: f64) -> Outcome {
        if self.turned_down {
            Outcome::Trapped { max_height_m: self.max_height_m, ground_distance_m: Some(distance_m) }
        } else {
            Outcome::Ground { distance_m }
        }
    }
}

/// The smallest t in [lo, hi] with h(t) < 0 (to 2⁻⁵⁰ of the interval), given h(hi) < 0;
/// h(lo) ≥ 0 is assumed, as at the start of a step above the ground.
fn first_below(h: &dyn Fn(f64) -> f64, lo: f64, hi: f64) -> f64 {
    let (mut a, mut b) = (lo, hi);
    for _ in 0..50 {
        let m = 0.5 * (a + b);
        if h(m) < 0.0 { b = m } else { a = m }
    }
    b
}

/// The fraction t ∈ [0, 1] where h is largest (`max`) or smallest, by golden-section search
/// (h is unimodal on a step that passes one turning point).
fn extremum(h: &dyn Fn(f64) -> f64, max: bool) -> f64 {
    let sign = if max { -1.0 } else { 1.0 };
    let f = |t: f64| sign * h(t);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (0.0, 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..60 {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

fn check_wavelength(atmosphere: &Atmosphere, wavelength_nm: f64) -> Result<()> {
    if !wavelength_nm.is_finite() {
        return Err(Error::input(None, format!("wavelength {wavelength_nm} nm must be a finite number")));
    }
    atmosphere.dispersion.check_range((wavelength_nm, wavelength_nm)).map_err(|e| Error::input(None, e))
}

/// Dormand–Prince with PI control and the settings' tolerances, no step bounds.
fn method(s: &Settings) -> Method {
    Method::DormandPrince { rtol: s.rtol, atol: s.atol, pi: true, h0: None, h_min: 0.0, h_max: f64::INFINITY }
}

fn check_inputs(atmosphere: &Atmosphere, wavelength_nm: f64, height_m: f64, s: &Settings) -> Result<()> {
    check_wavelength(atmosphere, wavelength_nm)?;
    method(s).validate()?;
    let top = atmosphere.top_m();
    if !(height_m.is_finite() && (0.0..top).contains(&height_m)) {
        return Err(Error::input(
            None,
            format!(
                "observer height {height_m} m is out of range; expected 0 m (the ground) up to the top of atmosphere \"{}\" at {top} m",
                atmosphere.name
            ),
        ));
    }
    if s.max_path_m.is_nan() || s.max_path_m <= 0.0 {
        return Err(Error::input(None, format!("max_path_m = {} m; expected a positive length", s.max_path_m)));
    }
    Ok(())
}
