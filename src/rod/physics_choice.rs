//! The model class chosen from the rod's own numbers: the rod model (`rod.model`), shear
//! deformation and rotary inertia (`rod.shear_deformation`), axial dynamics
//! (`rod.axial_dynamics`), and the model's share of the error estimate (`rod.error_estimate`).
//! `auto` settings are resolved here, once, when the model is built; the others are the user's.
//!
//! # Rod model
//! `rod.model = auto` takes the FFR rod where its linear modes hold at the load, the chain on its
//! modes (geometrically exact) where they do not. The load is predicted from the rod's numbers at
//! the design speed `omega` (`crank.design_speed`, else the crank speed at the start): the
//! crank pin's centripetal acceleration `r omega^2` loads the rod across with `q(x) = rho A r
//! omega^2 (1 - x / L)` where the crank stands across the rod, whose quasi-static midspan
//! deflection on pinned ends is `v_s = 5 q_0 L^4 / (768 E I)` (the simply supported beam under a
//! linearly varying load: W. C. Young and R. G. Budynas, *Roark's Formulas for Stress and
//! Strain*, 7th ed., 2002, table 8.1). The predicted peak `p = 2 v_s / L / (1 - (omega /
//! w_1)^2)` takes the suddenly applied load (factor 2) and the first harmonic's resonance (`w_1`
//! the pinned rod's first bending frequency; R. W. Clough and J. Penzien, *Dynamics of
//! Structures*, 1993, ch. 3) as amplifications; at or past resonance it is infinite. Length
//! means of the section stand for a tapered rod; gravity, the slider force and the axial
//! compression are left out (the compression by a heavy slider, taken as a static amplification
//! `1 / (1 - P / P_cr)`, predicted three to five times the measured peaks of the random rods). On
//! the benchmark rod it predicts 0.020 at 150 rad/s and 0.086 at 300 rad/s, against measured
//! abrupt-start peaks of 0.015 and 0.070; over the 44 random rods of docs/verification.md 1.3 to
//! 2.0 times the measured peak (an upper estimate). `auto` takes the chain on its modes where
//! the FFR rod's nonlinear share of the estimate at that peak, [`NONLINEAR_COEFFICIENT`] `p^2
//! sqrt(h / L)`, exceeds [`LARGE_DEFLECTION_SHARE`], with the segments the tolerance asks for
//! ([`auto_segments`]).
//!
//! # Shear deformation and rotary inertia
//! For a simply supported Timoshenko beam, mode n's frequency relative to the Euler-Bernoulli
//! beam's is, to first order in the slenderness,
//! `w_T^2 / w_EB^2 = 1 - (n pi r / L)^2 (1 + E / (k G))`, `r^2 = I / A`, `k A = A_s`
//! (S. P. Timoshenko, "On the correction for shear of the differential equation for transverse
//! vibrations of prismatic bars", Philosophical Magazine 41, 1921; S. M. Han, H. Benaroya and
//! T. Wei, "Dynamics of transversely vibrating beams using four engineering theories", Journal
//! of Sound and Vibration 225(5), 1999, eq. 60), and the compliance of the quasi-static first
//! mode grows by `(pi r / L)^2 E / (k G)`. The effect on `v_mid / L`, relative to its peak, is
//! taken as twice the first mode's relative change of `w^2`:
//! `e_shear = 2 (pi r / L)^2 (1 + E / (k G))`. The factor 2 stands for the dynamic response
//! (mode 3, the ringing, the amplification of the crank harmonics): over random rods of
//! slenderness 8 to 60 in the slider-crank, the measured effect of switching shear on was 0.5 to
//! 1.6 times `e_shear` in smooth starts (docs/verification.md, "Any rod"). `auto` switches shear
//! and rotary inertia on where `e_shear > solver.tolerance` in the FFR rod with consistent mass
//! and the chain on its modes (the full segment chain and lumped mass keep them off unless set
//! `on`; the error estimate then carries `e_shear`).
//!
//! # Axial dynamics
//! The slider-rod axial mode: the rod pinned axially at B, the masses at C (slider and small end,
//! `M`) on its free end; `beta tan(beta) = m / M` with `m` the rod's mass, `f_ax = beta c /
//! (2 pi L)`, `c = sqrt(E / rho)` (a bar with a tip mass: S. S. Rao, *Vibration of Continuous
//! Systems*, 2007, section 9.4, case "fixed-mass"); `beta = pi / 2` without a mass at C. `auto`
//! keeps it (FFR: as a mass-loaded mode, [`crate::modal::mass_loaded_modes`]; segments: the axial springs)
//! where it lies below [`AXIAL_BAND_FACTOR`] times the highest retained bending mode (the band
//! the start, the gas force and the retained modes excite), or where the masses at C reach the
//! rod's mass ([`super::spec::AXIAL_MODE_MASS_RATIO`]). With `auto`, an explicit `rod.axial_modes`
//! (FFR) is the scene's own choice and stands.

use super::spec::{PhysicsSwitch, RodModelKind, RodSpec, AXIAL_MODE_MASS_RATIO};
use crate::beam::section_table::DEFAULT_SHEAR_AREA_FACTOR;
use crate::beam::MassKind;
use crate::error::ModelError;
use std::f64::consts::PI;

/// The slider-rod axial mode is kept by `auto` below this multiple of the highest retained
/// bending frequency: below it the axial mode moves `v_mid` measurably, above it the crank
/// torque rings at a frequency a co-simulation master does not follow. Measured over random
/// rods and on the benchmark rod in docs/physics.md, "Model class chosen by the physics"
/// (axial dynamics).
pub const AXIAL_BAND_FACTOR: f64 = 1.5;

/// The integration's share of the error estimate, as a multiple of `solver.tolerance`: the error
/// control holds the pointwise error of `v_mid / L` below the tolerance, and over random
/// parameter sets it stays below a fifth of it (tests/error_control.rs).
pub const INTEGRATION_SHARE: f64 = 0.1;

/// The largest `rod.error_estimate`: an error of a thousand times the peak (no digit of the
/// output is right far below it).
pub const MAX_ERROR_ESTIMATE: f64 = 1e3;

/// The coefficient `C` of the share of what the FFR rod's linear modes with axial stiffening
/// leave out at large deflection, `C d^2 sqrt(h / L)` (`d` the forced deflection,
/// [`forced_deflection`]; `h = sqrt(12) r`, the depth of the rectangle of the same radius of
/// gyration). Calibrated on the 44 random rods against the geometrically exact shear beam:
/// docs/physics.md, "Model class chosen by the physics" (the error estimate).
pub const NONLINEAR_COEFFICIENT: f64 = 40.0;

/// The coefficient `C` of the segment chains' discretization share of the error estimate,
/// `C / N^2` for `N` segments (the chain converges at second order in `1 / N`). Measured against
/// the geometrically exact shear beam in docs/physics.md, "Model class chosen by the physics".
pub const CHAIN_DISCRETIZATION_COEFFICIENT: f64 = 1.4;

/// `rod.model = auto` takes the chain on its modes where the FFR rod's nonlinear share of the
/// error estimate at the predicted peak exceeds this (module docs, "Rod model"). Chosen on the
/// random rods: docs/physics.md, "Model class chosen by the physics".
pub const LARGE_DEFLECTION_SHARE: f64 = 8.5e-3;

/// The deflection of the forced motion, `|v_mid / L|`, from the peak so far and the amplitude of
/// the free vibration the start rang: `max(peak - start_vibration, peak / 2)`. The peak holds
/// the forced motion and the start's vibration at most added; the floor keeps the share where
/// the vibration is estimated too large (the quasi-static estimate of the start's vibration
/// against the reference runs of the random rods: docs/verification.md, "Any rod").
pub fn forced_deflection(peak: f64, start_vibration: f64) -> f64 {
    (peak - start_vibration).max(0.5 * peak)
}

/// The segment counts of the chain on its modes that `rod.model = auto` takes: the least `N`
/// whose discretization share [`CHAIN_DISCRETIZATION_COEFFICIENT`] `/ N^2` with the integration's
/// share [`INTEGRATION_SHARE`] stays within `solver.tolerance` (40 at 1e-3), at least
/// `AUTO_SEGMENTS.0` (16: 0.5 % measured at 300 rad/s) and `rod.elements`, at most
/// `AUTO_SEGMENTS.1` (64: below a tolerance of 4e-4 the estimate says the rest).
pub const AUTO_SEGMENTS: (usize, usize) = (16, 64);

/// The segment count `rod.model = auto` gives the chain on its modes for `tolerance` and
/// `rod.elements = elements` ([`AUTO_SEGMENTS`]).
pub fn auto_segments(tolerance: f64, elements: usize) -> usize {
    let share = (1.0 - INTEGRATION_SHARE) * tolerance;
    let needed = (CHAIN_DISCRETIZATION_COEFFICIENT / share).sqrt().ceil();
    let (low, high) = AUTO_SEGMENTS;
    let needed = if needed.is_finite() {
        (needed as usize).clamp(low, high)
    } else {
        high
    };
    needed.max(elements.min(high))
}

/// The operating point `rod.model = auto` chooses the rod model for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OperatingPoint {
    /// Crank length r, m.
    pub crank_length: f64,
    /// The highest crank speed `|omega|` of the run, rad/s.
    pub crank_speed: f64,
}

/// The predicted peak `|v_mid / L|` of `spec` at `op` (module docs, "Rod model"); infinite at or
/// past the first harmonic's resonance.
pub fn predicted_peak(spec: &RodSpec, op: &OperatingPoint) -> f64 {
    let p = spec.properties();
    let length = p.length;
    let rod_mass = spec
        .definition()
        .map(|d| d.rod_mass())
        .unwrap_or_else(|_| p.mass());
    let line_density = rod_mass / length;
    let bending = p.youngs_modulus * p.area_moment;
    let q0 = line_density * op.crank_length * op.crank_speed * op.crank_speed;
    let static_deflection = 5.0 * q0 * length.powi(4) / (768.0 * bending);
    let w1 = (PI / length).powi(2) * (bending / line_density).sqrt();
    let resonance = 1.0 - (op.crank_speed / w1).powi(2);
    let peak = 2.0 * static_deflection / length / resonance;
    if resonance > 0.0 && peak.is_finite() {
        peak
    } else {
        f64::INFINITY
    }
}

/// What `auto` chose, and the numbers it chose on.
#[derive(Clone, Debug, PartialEq)]
pub struct PhysicsChoice {
    /// The rod model built, and the setting it came from.
    pub model: RodModelKind,
    pub model_setting: RodModelKind,
    /// The operating point of `rod.model = auto` and its predicted peak `|v_mid / L|`
    /// ([`predicted_peak`]), with the FFR rod's nonlinear share there.
    pub operating_point: OperatingPoint,
    pub predicted_peak: f64,
    pub predicted_nonlinear_share: f64,
    /// Shear deformation and rotary inertia in the model.
    pub shear: bool,
    /// The setting it came from.
    pub shear_setting: PhysicsSwitch,
    /// `auto` may switch shear on in this model (the FFR rod with consistent mass).
    pub shear_possible: bool,
    /// `e_shear`: the estimated effect of shear and rotary inertia on `v_mid / L`, relative to
    /// its peak (module docs).
    pub shear_effect: f64,
    /// Axial dynamics in the model.
    pub axial: bool,
    pub axial_setting: PhysicsSwitch,
    /// The masses at C reach [`AXIAL_MODE_MASS_RATIO`] times the rod's.
    pub heavy_at_c: bool,
    /// `auto` with an explicit `rod.axial_modes`: the scene's count decided.
    pub axial_count_given: bool,
    /// The slider-rod axial frequency, Hz.
    pub axial_hz: f64,
    /// The highest retained bending frequency (estimate: the simply supported rod's mode
    /// `modes`, or the mode band), Hz.
    pub band_top_hz: f64,
    /// The mode band `rod.mode_band_hz` where the scene gives one: `band_top_hz` is then the
    /// band's limit (at least the first bending mode), not a retained mode.
    pub mode_band_hz: Option<f64>,
    /// The tolerance the choice was made for.
    pub tolerance: f64,
    /// `h / L` with `h = sqrt(12 I / A)` (the section's length means).
    pub depth_ratio: f64,
    /// The segment chain: no share for the nonlinear terms.
    pub geometrically_exact: bool,
    /// The segment chains' discretization share, [`CHAIN_DISCRETIZATION_COEFFICIENT`] `/ N^2`
    /// (0 for the FFR rod).
    pub discretization: f64,
}

impl PhysicsChoice {
    /// The model's share of the error estimate, relative to the peak of `v_mid / L`: the
    /// effect of what is left out (shear and rotary inertia where off).
    pub fn model_error(&self) -> f64 {
        if self.shear {
            0.0
        } else {
            self.shear_effect
        }
    }

    /// `rod.error_estimate`: the estimated error of `v_mid / L` relative to its peak, model and
    /// integration together, for a motion whose peak `|v_mid / L|` so far is `peak` and whose
    /// start rang a free vibration of amplitude `start_vibration` (`v_mid / L`;
    /// `Mechanism::start_vibration`, 0 after a start from rest): [`Self::model_error`] +
    /// [`INTEGRATION_SHARE`] `solver.tolerance` + [`NONLINEAR_COEFFICIENT`] `d^2 sqrt(h / L)`
    /// with `d` the forced deflection ([`forced_deflection`]; FFR rod, the segment chain is
    /// geometrically exact) + the chains' discretization share.
    pub fn error_estimate(&self, peak: f64, start_vibration: f64) -> f64 {
        let forced = forced_deflection(peak, start_vibration);
        let nonlinear = if self.geometrically_exact {
            0.0
        } else {
            NONLINEAR_COEFFICIENT * forced * forced * self.depth_ratio.sqrt()
        };
        let estimate = self.model_error()
            + INTEGRATION_SHARE * self.tolerance
            + nonlinear
            + self.discretization;
        // Finite whatever the parameters (a shear area of 1e-320 m^2 makes e_shear infinite):
        // past MAX_ERROR_ESTIMATE times the peak it says no more.
        if estimate.is_finite() {
            estimate.min(MAX_ERROR_ESTIMATE)
        } else {
            MAX_ERROR_ESTIMATE
        }
    }

    /// What was chosen, in a few words: "shear on, axial dynamics off".
    pub fn summary(&self) -> String {
        let on_off = |b: bool| if b { "on" } else { "off" };
        let chain = if self.discretization > 0.0 {
            format!(
                ", chain discretization {:.1e} (rod.elements)",
                self.discretization
            )
        } else {
            String::new()
        };
        format!(
            "shear deformation {}, axial dynamics {}{chain}",
            on_off(self.shear),
            on_off(self.axial)
        )
    }

    /// What was chosen and why, for the log at the end of initialization.
    pub fn describe(&self) -> String {
        let why = |setting: PhysicsSwitch, auto_reason: String| match setting {
            PhysicsSwitch::Auto => auto_reason,
            s => format!("set {}", s.name()),
        };
        let on_off = |b: bool| if b { "on" } else { "off" };
        let shear_reason = if self.shear_possible || self.shear_effect <= self.tolerance {
            format!(
                "auto: estimated effect on v_mid/L {:.1e} of its peak {} solver.tolerance {:.0e}",
                self.shear_effect,
                if self.shear_effect > self.tolerance {
                    ">"
                } else {
                    "<="
                },
                self.tolerance
            )
        } else {
            format!(
                "auto keeps it off in this model (the segment chain, or lumped mass), although its estimated effect on v_mid/L, {:.1e} of its peak, exceeds solver.tolerance {:.0e}: rod.error_estimate carries it; set rod.shear_deformation = on to include it",
                self.shear_effect, self.tolerance
            )
        };
        let band = match self.mode_band_hz {
            Some(band) if band >= self.band_top_hz => format!(
                "the mode band's limit rod.mode_band_hz = {:.0} Hz (the retained modes lie below it)",
                self.band_top_hz
            ),
            Some(_) => format!(
                "the first bending mode, estimated {:.0} Hz (above rod.mode_band_hz)",
                self.band_top_hz
            ),
            None => format!(
                "the highest retained bending mode, estimated {:.0} Hz",
                self.band_top_hz
            ),
        };
        let axial_reason = format!(
            "auto: slider-rod axial mode {:.0} Hz against {AXIAL_BAND_FACTOR} x {band}{}",
            self.axial_hz,
            if self.heavy_at_c {
                "; the masses at C reach the rod's"
            } else {
                ""
            }
        );
        let axial_reason = if self.axial_count_given {
            "rod.axial_modes given".to_string()
        } else {
            axial_reason
        };
        let model_reason = match self.model_setting {
            RodModelKind::Auto => format!(
                "auto: predicted peak |v_mid/L| {:.2e} at crank.design_speed {} rad/s, the FFR rod's nonlinear share there {:.1e} {} {LARGE_DEFLECTION_SHARE:e}{}",
                self.predicted_peak,
                self.operating_point.crank_speed,
                self.predicted_nonlinear_share,
                if self.model == RodModelKind::Ffr { "<=" } else { ">" },
                if self.model == RodModelKind::Ffr {
                    ""
                } else {
                    ": geometrically exact"
                }
            ),
            s => format!("set {}", s.name()),
        };
        format!(
            "rod model {} ({model_reason}); shear deformation and rotary inertia {} ({}); axial dynamics {} ({})",
            self.model.name(),
            on_off(self.shear),
            why(self.shear_setting, shear_reason),
            on_off(self.axial),
            why(self.axial_setting, axial_reason)
        )
    }
}

/// `e_shear` of `spec` (module docs), from the section's length means.
pub fn shear_effect(spec: &RodSpec) -> f64 {
    let p = spec.properties();
    let e = p.youngs_modulus;
    let g = spec
        .shear_modulus
        .unwrap_or(e * super::spec::DEFAULT_SHEAR_MODULUS_FACTOR);
    let shear_area = match (&spec.shear_area, spec.section.is_empty()) {
        (Some(a_s), _) => *a_s,
        (None, true) => p.area * DEFAULT_SHEAR_AREA_FACTOR,
        (None, false) => {
            let n = spec.section.len() as f64;
            spec.section
                .iter()
                .map(|st| st.shear_area.unwrap_or(st.area * DEFAULT_SHEAR_AREA_FACTOR))
                .sum::<f64>()
                / n
        }
    };
    let r2 = p.area_moment / p.area;
    let slenderness = PI * PI * r2 / (p.length * p.length);
    2.0 * slenderness * (1.0 + e * p.area / (g * shear_area))
}

/// The slider-rod axial frequency, Hz, with `mass_at_c` kg at C (module docs).
pub fn axial_frequency_hz(spec: &RodSpec, mass_at_c: f64) -> f64 {
    let p = spec.properties();
    let c = (p.youngs_modulus / p.density).sqrt();
    let m = spec
        .definition()
        .map(|d| d.rod_mass())
        .unwrap_or_else(|_| p.mass());
    let beta = tip_mass_root(m, mass_at_c);
    beta * c / (2.0 * PI * p.length)
}

/// The first root of `beta tan(beta) = m / M` in (0, pi/2]; `pi / 2` for `M = 0`.
fn tip_mass_root(m: f64, mass_at_c: f64) -> f64 {
    let positive = |x: f64| x > 0.0;
    if !positive(mass_at_c) || !positive(m) {
        return PI / 2.0;
    }
    let ratio = m / mass_at_c;
    // f(beta) = beta sin - ratio cos is increasing on (0, pi/2): bisection, then it is exact
    // to the last bits after 60 halvings.
    let (mut lo, mut hi) = (0.0_f64, PI / 2.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if mid * mid.sin() - ratio * mid.cos() < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The first bending frequency of the simply supported Euler-Bernoulli rod of `spec`'s length
/// means, Hz: `(pi / L)^2 sqrt(E I / (rho A)) / (2 pi)`.
fn first_bending_hz(spec: &RodSpec) -> f64 {
    let p = spec.properties();
    (PI / p.length).powi(2) * (p.youngs_modulus * p.area_moment / (p.density * p.area)).sqrt()
        / (2.0 * PI)
}

/// The rod model `rod.model = auto` takes for `spec` at `op` and `tolerance` (module docs, "Rod
/// model"): the model (with its `rod.elements`), the predicted peak and the FFR rod's nonlinear
/// share there. Any other setting stands.
pub fn resolve_model(
    spec: &RodSpec,
    tolerance: f64,
    op: &OperatingPoint,
) -> (RodModelKind, usize, f64, f64) {
    let peak = predicted_peak(spec, op);
    let p = spec.properties();
    let depth_ratio = (12.0 * p.area_moment / p.area).sqrt() / p.length;
    let share = NONLINEAR_COEFFICIENT * peak * peak * depth_ratio.sqrt();
    match spec.model {
        RodModelKind::Auto if share > LARGE_DEFLECTION_SHARE || !share.is_finite() => (
            RodModelKind::ModalSegments,
            auto_segments(tolerance, spec.elements),
            peak,
            share,
        ),
        RodModelKind::Auto => (RodModelKind::Ffr, spec.elements, peak, share),
        model => (model, spec.elements, peak, share),
    }
}

/// Resolve the `auto` settings of `spec` for a slider of `slider_mass` kg, the tolerance
/// `tolerance` and the operating point `op`: the spec the model is built from (the rod model
/// chosen, every switch `on` or `off`, the axial mode expressed in `axial_modes`,
/// `loaded_modes` or `axial_springs`), and what was chosen.
pub fn choose(
    spec: &RodSpec,
    slider_mass: f64,
    tolerance: f64,
    op: &OperatingPoint,
) -> Result<(RodSpec, PhysicsChoice), ModelError> {
    spec.validate()?;
    let model_setting = spec.model;
    let (model, elements, predicted_peak, predicted_nonlinear_share) =
        resolve_model(spec, tolerance, op);
    let spec = &RodSpec {
        model,
        elements,
        ..spec.clone()
    };
    spec.validate()?;
    let shear_effect = shear_effect(spec);
    // `auto` takes shear into the FFR rod with consistent mass and into the chain on its modes
    // (the shear slides' stiff motions lie in the modes left out): lumped element mass exists
    // for the Euler-Bernoulli rod alone, and the full segment chain's shear slides are stiff
    // joints its Newton iteration does not always pass at large deflections (the benchmark rod
    // at E / 100, v/L 0.4). There the error estimate carries the effect left out; `on` is the
    // user's to set.
    let shear_possible = match spec.model {
        RodModelKind::Ffr => spec.mass == MassKind::Consistent,
        RodModelKind::ModalSegments => true,
        RodModelKind::Segments | RodModelKind::Auto => false,
    };
    let shear = match spec.shear_deformation {
        PhysicsSwitch::Auto => shear_possible && shear_effect > tolerance,
        s => s == PhysicsSwitch::On,
    };
    let mass_at_c = slider_mass + spec.small_end.mass;
    let axial_hz = axial_frequency_hz(spec, mass_at_c);
    let f1 = first_bending_hz(spec);
    let band_top_hz = match spec.mode_band_hz {
        Some(band) => band.max(f1),
        None => {
            let n = spec.modes.max(1) as f64;
            n * n * f1
        }
    };
    let heavy_at_c = {
        let rod = spec.total_mass().unwrap_or(f64::INFINITY);
        mass_at_c > 0.0 && mass_at_c >= AXIAL_MODE_MASS_RATIO * rod
    };
    // An explicit `rod.axial_modes` with `auto` is the scene's own choice of axial modes (free
    // or mass-loaded as `rod.loaded_modes` says): kept as it is.
    let explicit_count = match (spec.model, spec.axial_dynamics, spec.axial_modes) {
        (RodModelKind::Ffr, PhysicsSwitch::Auto, Some(n)) => Some(n),
        _ => None,
    };
    let axial = match (spec.axial_dynamics, explicit_count) {
        (_, Some(n)) => n > 0,
        (PhysicsSwitch::Auto, None) => heavy_at_c || axial_hz <= AXIAL_BAND_FACTOR * band_top_hz,
        (s, None) => s == PhysicsSwitch::On,
    };
    let mut resolved = spec.clone();
    resolved.axial_in_addition = false;
    resolved.shear_deformation = PhysicsSwitch::from_bool(shear);
    resolved.axial_dynamics = PhysicsSwitch::from_bool(axial);
    if !shear {
        resolved.shear_modulus = None;
        resolved.shear_area = None;
    }
    match spec.model {
        RodModelKind::Ffr if explicit_count.is_some() => {}
        RodModelKind::Ffr if axial => {
            resolved.loaded_modes = true;
            resolved.axial_modes = Some(spec.axial_modes.unwrap_or(1).max(1));
            // The scene's own `rod.axial_modes` counts every mode, as with `auto`; a spec
            // resolved before keeps its count (resolving is idempotent).
            resolved.axial_in_addition = spec.axial_in_addition || spec.axial_modes.is_none();
        }
        RodModelKind::Ffr => {
            resolved.axial_modes = Some(spec.axial_modes.unwrap_or(0));
        }
        RodModelKind::Segments => resolved.axial_springs = spec.axial_springs || axial,
        RodModelKind::ModalSegments | RodModelKind::Auto => {
            resolved.axial_springs = spec.axial_springs || axial
        }
    }
    let choice = PhysicsChoice {
        model,
        model_setting,
        operating_point: *op,
        predicted_peak,
        predicted_nonlinear_share,
        shear,
        shear_setting: spec.shear_deformation,
        shear_possible,
        shear_effect,
        axial,
        axial_setting: spec.axial_dynamics,
        axial_count_given: explicit_count.is_some(),
        heavy_at_c,
        axial_hz,
        band_top_hz,
        mode_band_hz: spec.mode_band_hz,
        tolerance,
        geometrically_exact: spec.model != RodModelKind::Ffr,
        discretization: match spec.model {
            RodModelKind::Ffr => 0.0,
            _ => CHAIN_DISCRETIZATION_COEFFICIENT / (spec.elements.max(1) as f64).powi(2),
        },
        depth_ratio: {
            let p = spec.properties();
            (12.0 * p.area_moment / p.area).sqrt() / p.length
        },
    };
    Ok((resolved, choice))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The benchmark scene's crank at 150 rad/s.
    const BENCHMARK_150: OperatingPoint = OperatingPoint {
        crank_length: 0.1524,
        crank_speed: 150.0,
    };

    #[test]
    fn auto_takes_the_chain_where_the_load_is_large() {
        let mut spec = benchmark_rod();
        spec.model = RodModelKind::Auto;
        let at = |w: f64| OperatingPoint {
            crank_speed: w,
            ..BENCHMARK_150
        };
        // The numbers of the module docs: 0.020 at 150 rad/s, 0.086 at 300 rad/s.
        let resolve = |spec: &RodSpec, w: f64| resolve_model(spec, 1e-3, &at(w));
        let (model, elements, peak, share) = resolve(&spec, 150.0);
        assert_eq!((model, elements), (RodModelKind::Ffr, 8));
        assert!(
            (peak - 0.0196).abs() < 5e-4 && share < LARGE_DEFLECTION_SHARE,
            "{peak} {share}"
        );
        let (model, elements, peak, _) = resolve(&spec, 300.0);
        assert_eq!((model, elements), (RodModelKind::ModalSegments, 40));
        assert!((peak - 0.0864).abs() < 1e-3, "{peak}");
        // The switch near 210 rad/s; the chain past resonance, and at rest the FFR rod.
        assert_eq!(resolve(&spec, 200.0).0, RodModelKind::Ffr);
        assert_eq!(resolve(&spec, 220.0).0, RodModelKind::ModalSegments);
        assert_eq!(resolve(&spec, 0.0).0, RodModelKind::Ffr);
        assert!(predicted_peak(&spec, &at(900.0)).is_infinite());
        // More segments asked for are kept.
        spec.elements = 48;
        assert_eq!(resolve(&spec, 300.0).1, 48);
        // The segments follow the tolerance: the estimate's chain share and integration share
        // within it, between 16 and 64.
        for (tolerance, n) in [(1e-3, 40), (3e-3, 23), (0.1, 16), (1e-4, 64), (1e-10, 64)] {
            assert_eq!(auto_segments(tolerance, 8), n, "{tolerance}");
        }
        let n = auto_segments(1e-3, 8) as f64;
        assert!(CHAIN_DISCRETIZATION_COEFFICIENT / (n * n) + INTEGRATION_SHARE * 1e-3 <= 1e-3);
        let n = n - 1.0;
        assert!(CHAIN_DISCRETIZATION_COEFFICIENT / (n * n) + INTEGRATION_SHARE * 1e-3 > 1e-3);
        // Any other setting stands.
        spec.model = RodModelKind::Ffr;
        assert_eq!(resolve(&spec, 300.0).0, RodModelKind::Ffr);
        spec.model = RodModelKind::Auto;
        let (resolved, choice) = choose(&spec, 0.0, 1e-3, &at(300.0)).unwrap();
        assert_eq!(resolved.model, RodModelKind::ModalSegments);
        assert!(choice.geometrically_exact && choice.shear);
        assert!(choice
            .describe()
            .starts_with("rod model modal_segments (auto: predicted peak"));
    }

    /// The CDI benchmark rod of the default scene (J. O'Shea, table 3).
    fn benchmark_rod() -> RodSpec {
        toml::from_str(
            "model = \"ffr\"\nlength = 0.3048\nyoungs_modulus = 2.068e11\ndensity = 7833.8\narea = 3.167e-5\narea_moment = 7.981e-11\nelements = 8\nmodes = 3",
        )
        .expect("a valid rod")
    }

    #[test]
    fn tip_mass_root_solves_the_frequency_equation() {
        for ratio in [0.01, 0.5, 1.0, 2.0, 100.0] {
            let b = tip_mass_root(ratio, 1.0);
            assert!(
                (b * b.tan() - ratio).abs() < 1e-9 * ratio.max(1.0),
                "{ratio}: {b}"
            );
        }
        assert_eq!(tip_mass_root(1.0, 0.0), PI / 2.0);
    }

    #[test]
    fn shear_effect_follows_the_slenderness() {
        let mut spec = benchmark_rod();
        let e0 = shear_effect(&spec);
        // (pi r / L)^2 (1 + 2.6 * 1.2) * 2 with r^2 = I / A.
        let p = spec.properties();
        let expected = 2.0 * PI * PI * p.area_moment / p.area / p.length.powi(2) * (1.0 + 3.12);
        assert!((e0 - expected).abs() < 1e-12 * expected);
        spec.length *= 2.0;
        assert!((shear_effect(&spec) - e0 / 4.0).abs() < 1e-12 * e0);
    }

    #[test]
    fn the_estimate_is_finite_for_any_parameters() {
        let mut spec = benchmark_rod();
        spec.shear_deformation = PhysicsSwitch::Off;
        spec.shear_area = Some(1e-320);
        let (_, c) = choose(&spec, 0.0, 1e-3, &BENCHMARK_150).unwrap();
        assert!(shear_effect(&spec).is_infinite());
        assert_eq!(c.error_estimate(0.01, 0.0), MAX_ERROR_ESTIMATE);
        assert_eq!(c.error_estimate(1e200, 0.0), MAX_ERROR_ESTIMATE);
    }

    /// The forced deflection is the peak less the start's vibration, at least half the peak; the
    /// estimate's nonlinear share goes with its square and nothing else changes.
    #[test]
    fn the_nonlinear_share_takes_the_forced_deflection() {
        assert_eq!(forced_deflection(0.01, 0.0), 0.01);
        assert_eq!(forced_deflection(0.01, 0.003), 0.007);
        assert_eq!(forced_deflection(0.01, 0.008), 0.005);
        let (_, c) = choose(&benchmark_rod(), 0.0, 1e-3, &BENCHMARK_150).unwrap();
        let fixed = c.error_estimate(0.0, 0.0);
        let share = |peak: f64, vibration: f64| c.error_estimate(peak, vibration) - fixed;
        assert!((share(0.01, 0.003) / share(0.01, 0.0) - 0.49).abs() < 1e-12);
        assert_eq!(share(0.007, 0.0), share(0.01, 0.003));
    }

    /// Where `auto` cannot take shear in (the segment chain) the log says so and names the
    /// effect left to the error estimate, instead of an "off" beside "effect > tolerance".
    #[test]
    fn auto_says_why_the_chain_keeps_shear_off() {
        let mut spec = benchmark_rod();
        let (_, ffr) = choose(&spec, 0.0, 1e-4, &BENCHMARK_150).unwrap();
        assert!(ffr.shear && ffr.describe().contains("on (auto: estimated effect"));
        spec.model = RodModelKind::Segments;
        let (_, chain) = choose(&spec, 0.0, 1e-4, &BENCHMARK_150).unwrap();
        let text = chain.describe();
        assert!(!chain.shear, "{text}");
        assert!(text.contains("auto keeps it off in this model"), "{text}");
        assert!(text.contains("rod.shear_deformation = on"), "{text}");
        assert_eq!(chain.model_error(), chain.shear_effect);
        let (_, loose) = choose(&spec, 0.0, 0.1, &BENCHMARK_150).unwrap();
        assert!(
            loose.describe().contains("<= solver.tolerance"),
            "{}",
            loose.describe()
        );
    }

    #[test]
    fn settings_on_and_off_are_kept() {
        let mut spec = benchmark_rod();
        spec.shear_deformation = PhysicsSwitch::Off;
        spec.axial_dynamics = PhysicsSwitch::On;
        let (r, c) = choose(&spec, 0.0, 1e-12, &BENCHMARK_150).unwrap();
        assert!(!c.shear && c.axial);
        assert_eq!(r.shear_deformation, PhysicsSwitch::Off);
        assert!(r.loaded_modes && r.axial_modes == Some(1));
        // `rod.modes` counts bending modes, the axial mode in addition; a scene's own
        // `rod.axial_modes` counts every mode.
        assert!(r.axial_in_addition);
        let (again, _) = choose(&r, 0.0, 1e-12, &BENCHMARK_150).unwrap();
        assert_eq!(again, r, "resolving a resolved spec changes nothing");
        spec.axial_modes = Some(1);
        let (r, _) = choose(&spec, 0.0, 1e-12, &BENCHMARK_150).unwrap();
        assert!(!r.axial_in_addition);
        spec.axial_modes = None;
        spec.shear_deformation = PhysicsSwitch::On;
        spec.axial_dynamics = PhysicsSwitch::Off;
        spec.axial_in_addition = true;
        let (r, c) = choose(&spec, 10.0, 0.1, &BENCHMARK_150).unwrap();
        assert!(c.shear && !c.axial);
        assert_eq!(r.axial_modes, Some(0));
        assert!(
            !r.axial_in_addition,
            "without axial dynamics the count is of every mode"
        );
    }

    #[test]
    fn auto_follows_the_tolerance_and_the_band() {
        let spec = benchmark_rod();
        let effect = shear_effect(&spec);
        assert!(
            choose(&spec, 0.0, effect * 0.9, &BENCHMARK_150)
                .unwrap()
                .1
                .shear
        );
        assert!(
            !choose(&spec, 0.0, effect * 1.1, &BENCHMARK_150)
                .unwrap()
                .1
                .shear
        );
        // Benchmark rod: axial 4.2 kHz, three modes up to 1.24 kHz: no axial mode; a slider
        // of 10 times the rod's mass brings it down to 0.7 kHz.
        let (_, c) = choose(&spec, 0.0, 1e-3, &BENCHMARK_150).unwrap();
        assert!(!c.axial, "{}", c.describe());
        assert!((c.axial_hz - 4214.0).abs() < 10.0, "{}", c.axial_hz);
        let m = spec.total_mass().unwrap();
        let (_, c) = choose(&spec, 10.0 * m, 1e-3, &BENCHMARK_150).unwrap();
        assert!(c.axial, "{}", c.describe());
    }
}
