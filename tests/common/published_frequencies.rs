//! The published frequency tables (docs/physics.md, "Verification: frequencies and closed
//! forms"): the connecting rod in 2 elements, consistent mass, Hz. From O. P. Agrawal and
//! A. A. Shabana, "Dynamic analysis of multibody systems using component modes", Computers &
//! Structures 21(6), 1985, section 7, and J. O'Shea (Computational Dynamics Inc.), "CDI
//! Parametric Study: Analysis of the Small-Deformation Connecting Rod: Slider Crank Mechanism"
//! (the benchmark note), table 4.

/// The benchmark note's rod density, kg/m^3 (the default scene's).
pub const CDI_DENSITY: f64 = 7833.8;

/// Agrawal and Shabana's density, kg/m^3: reproduces all four of their frequency lists.
pub const AGRAWAL_SHABANA_DENSITY: f64 = 8143.1;

/// The benchmark note, simply supported (printed to 4 significant digits).
pub const CDI_SIMPLY_SUPPORTED: [f64; 6] = [138.5, 612.3, 1539.0, 2806.0, 4323.0, 15100.0];

/// The benchmark note, free-free (4 significant digits; docs/physics.md: its 980.7 and 3918 Hz
/// are 980.58 and 3917.25 Hz for these data).
pub const CDI_FREE_FREE: [f64; 6] = [313.3, 980.6, 2452.0, 3917.0, 9294.0, 18590.0];

/// Agrawal and Shabana, section 7 (printed to two decimals), by reference conditions.
pub const AGRAWAL_SHABANA_SIMPLY_SUPPORTED: [f64; 6] =
    [135.80, 600.52, 1509.45, 2751.91, 4240.25, 14812.84];
pub const AGRAWAL_SHABANA_MEAN_AXIS: [f64; 6] =
    [307.31, 961.77, 2404.94, 3842.11, 9115.38, 18230.77];
pub const AGRAWAL_SHABANA_BODY_FIXED_MID: [f64; 6] =
    [193.66, 193.66, 1908.09, 1908.09, 9115.38, 9115.38];
pub const AGRAWAL_SHABANA_CANTILEVER: [f64; 6] =
    [48.21, 304.54, 1030.02, 2989.54, 4240.25, 14812.84];

/// Agrawal and Shabana's lists by the scene's name of the reference conditions.
pub const AGRAWAL_SHABANA: [(&str, [f64; 6]); 4] = [
    ("simply_supported", AGRAWAL_SHABANA_SIMPLY_SUPPORTED),
    ("mean_axis", AGRAWAL_SHABANA_MEAN_AXIS),
    ("body_fixed_mid", AGRAWAL_SHABANA_BODY_FIXED_MID),
    ("cantilever", AGRAWAL_SHABANA_CANTILEVER),
];
