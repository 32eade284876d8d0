//! The twelve equation forms of the Urban Tree Database (its table TS4) and one fitted equation
//! with its range. Values follow the published forms literally, including the quirk of
//! `loglogw1`, whose bias correction sits inside the outer logarithm.

use std::fmt;

/// One of the database's twelve equation forms.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Form {
    /// a + b x
    Lin,
    /// a + b x + c x²
    Quad,
    /// a + b x + c x² + d x³
    Cub,
    /// a + b x + c x² + d x³ + e x⁴
    Quart,
    /// exp(a + b ln(ln(x + 1) + mse/2))
    LogLogW1,
    /// exp(a + b ln(ln(x + 1)) + √x mse/2)
    LogLogW2,
    /// exp(a + b ln(ln(x + 1)) + x mse/2)
    LogLogW3,
    /// exp(a + b ln(ln(x + 1)) + x² mse/2)
    LogLogW4,
    /// exp(a + b x + mse/2)
    ExPow1,
    /// exp(a + b x + √x mse/2)
    ExPow2,
    /// exp(a + b x + x mse/2)
    ExPow3,
    /// exp(a + b x + x² mse/2)
    ExPow4,
}

impl Form {
    /// All forms, in the order of the database's table TS4 after the polynomials.
    pub const ALL: [Form; 12] = [
        Form::Lin,
        Form::Quad,
        Form::Cub,
        Form::Quart,
        Form::LogLogW1,
        Form::LogLogW2,
        Form::LogLogW3,
        Form::LogLogW4,
        Form::ExPow1,
        Form::ExPow2,
        Form::ExPow3,
        Form::ExPow4,
    ];

    /// The database's name of the form (`EqName`).
    pub fn name(self) -> &'static str {
        match self {
            Form::Lin => "lin",
            Form::Quad => "quad",
            Form::Cub => "cub",
            Form::Quart => "quart",
            Form::LogLogW1 => "loglogw1",
            Form::LogLogW2 => "loglogw2",
            Form::LogLogW3 => "loglogw3",
            Form::LogLogW4 => "loglogw4",
            Form::ExPow1 => "expow1",
            Form::ExPow2 => "expow2",
            Form::ExPow3 => "expow3",
            Form::ExPow4 => "expow4",
        }
    }

    /// The form named `name` (case-insensitive), if any.
    pub fn from_name(name: &str) -> Option<Form> {
        let name = name.trim();
        Form::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(name))
    }

    /// Polynomial forms are defined at 0; the log-log forms are not (ln(ln(1)) = -inf).
    pub fn is_polynomial(self) -> bool {
        matches!(self, Form::Lin | Form::Quad | Form::Cub | Form::Quart)
    }

    /// Log-log forms need x > 0.
    pub fn is_log_log(self) -> bool {
        matches!(
            self,
            Form::LogLogW1 | Form::LogLogW2 | Form::LogLogW3 | Form::LogLogW4
        )
    }
}

impl fmt::Display for Form {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A fitted equation: its form, coefficients a..e, the mean squared error used by the log-log
/// and exponential forms, and the range its predictions are valid in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Equation {
    /// Which of the twelve forms.
    pub form: Form,
    /// Coefficients a, b, c, d, e (unused ones 0).
    pub coefficients: [f64; 5],
    /// The bias-correction term of the log-log and exponential forms (the database's column c,
    /// or d where d is filled).
    pub mse: f64,
    /// Smallest and largest predicted value the fit is meant for ("Apps min/max": ranges of the
    /// prediction, not of the input).
    pub range: (f64, f64),
}

impl Equation {
    /// The form evaluated literally at `x`, with no clamping (NaN or infinite where the form is
    /// undefined, as a log-log form at 0).
    pub fn raw(&self, x: f64) -> f64 {
        let [a, b, c, d, e] = self.coefficients;
        let half = self.mse / 2.0;
        let ll = || (x + 1.0).ln().ln();
        match self.form {
            Form::Lin => a + b * x,
            Form::Quad => a + x * (b + x * c),
            Form::Cub => a + x * (b + x * (c + x * d)),
            Form::Quart => a + x * (b + x * (c + x * (d + x * e))),
            Form::LogLogW1 => (a + b * ((x + 1.0).ln() + half).ln()).exp(),
            Form::LogLogW2 => (a + b * ll() + x.sqrt() * half).exp(),
            Form::LogLogW3 => (a + b * ll() + x * half).exp(),
            Form::LogLogW4 => (a + b * ll() + x * x * half).exp(),
            Form::ExPow1 => (a + b * x + half).exp(),
            Form::ExPow2 => (a + b * x + x.sqrt() * half).exp(),
            Form::ExPow3 => (a + b * x + x * half).exp(),
            Form::ExPow4 => (a + b * x + x * x * half).exp(),
        }
    }

    /// The first x in `[from, to]` where the equation rises (`from` when it rises there).
    pub fn rise_start(&self, from: f64, to: f64) -> f64 {
        let h = (to - from) / 3000.0;
        let mut x = from;
        while x < to
            && self.raw(x + h).partial_cmp(&self.raw(x)) != Some(std::cmp::Ordering::Greater)
        {
            x += h;
        }
        x
    }

    /// Where the equation, rising from `from`, stops rising within `[from, to]`: the vertex of
    /// a quadratic that turns over, the first maximum of a cubic. `to` when it rises throughout.
    /// Found on a fine grid and refined by bisection on the slope's sign.
    pub fn rise_end(&self, from: f64, to: f64) -> f64 {
        const STEPS: usize = 2000;
        let h = (to - from) / STEPS as f64;
        if h <= 0.0 {
            return from;
        }
        let slope = |x: f64| {
            let e = h * 1e-3;
            self.raw(x + e) - self.raw(x - e)
        };
        let mut prev = from;
        for i in 1..=STEPS {
            let x = from + h * i as f64;
            if slope(x).is_nan() || slope(x) <= 0.0 {
                let (mut lo, mut hi) = (prev, x);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if slope(mid) > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                return lo;
            }
            prev = x;
        }
        to
    }
}
