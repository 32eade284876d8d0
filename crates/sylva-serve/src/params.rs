//! The API's query parameters, each checked with a message that names it and says what is
//! allowed: the body of an HTTP 400.

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use std::collections::HashMap;
use sylva::growth::{Database, Measured};

/// Most species one request may compare, as the page allows.
pub const MAX_SPECIES: usize = 4;

/// A request the API refuses, with its status and a JSON body
/// `{"error": ..., "parameter": ..., "allowed": ...}`.
#[derive(Debug)]
pub struct ApiError {
    /// 400 for bad parameters, 503 when busy, 500 when a picture cannot be drawn.
    pub status: StatusCode,
    /// The parameter at fault, if one is.
    pub parameter: Option<&'static str>,
    /// What is wrong.
    pub message: String,
    /// What is allowed.
    pub allowed: Option<String>,
    /// For a 503: when to ask again, and what the server is busy with.
    pub busy: Option<Busy>,
}

/// Why a request was answered 503, and when to ask again: the `Retry-After` header, and
/// `retry_after` and `growing` in the body, from which the page says what it waits for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Busy {
    /// Seconds to wait before asking again.
    pub retry_after: u32,
    /// Growths running.
    pub growing: usize,
}

impl ApiError {
    /// A bad parameter.
    pub fn bad(parameter: &'static str, message: String, allowed: impl Into<String>) -> Self {
        ApiError {
            status: StatusCode::BAD_REQUEST,
            parameter: Some(parameter),
            message: format!("{parameter}: {message}"),
            allowed: Some(allowed.into()),
            busy: None,
        }
    }

    /// A failure of the server's own (a renderer that will not start, a file that will not
    /// write).
    pub fn internal(message: String) -> Self {
        ApiError {
            status: StatusCode::INTERNAL_SERVER_ERROR,
            parameter: None,
            message,
            allowed: None,
            busy: None,
        }
    }

    /// A 503: the server cannot take this on now; `busy` says when to ask again.
    pub fn busy(message: String, busy: Busy) -> Self {
        ApiError {
            status: StatusCode::SERVICE_UNAVAILABLE,
            parameter: None,
            message,
            allowed: None,
            busy: Some(busy),
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let mut body = serde_json::json!({
            "error": self.message,
            "parameter": self.parameter,
            "allowed": self.allowed,
        });
        let Some(busy) = self.busy else {
            return (self.status, Json(body)).into_response();
        };
        body["retry_after"] = busy.retry_after.into();
        body["growing"] = busy.growing.into();
        let retry = [(
            axum::http::header::RETRY_AFTER,
            busy.retry_after.to_string(),
        )];
        (self.status, retry, Json(body)).into_response()
    }
}

/// A request's query string, as pairs.
pub struct Query<'a>(pub &'a HashMap<String, String>);

impl Query<'_> {
    /// The region (default `InlVal`, Modesto), as the database spells it.
    pub fn region(&self, db: &Database) -> Result<String, ApiError> {
        let given = self.0.get("region").map_or("InlVal", String::as_str);
        db.regions()
            .iter()
            .find(|r| r.code.eq_ignore_ascii_case(given))
            .map(|r| r.code.clone())
            .ok_or_else(|| {
                let codes: Vec<&str> = db.regions().iter().map(|r| r.code.as_str()).collect();
                ApiError::bad(
                    "region",
                    format!("`{given}` is not a region of the Urban Tree Database"),
                    codes.join(", "),
                )
            })
    }

    /// The species (1 to [`MAX_SPECIES`], comma-separated codes, scientific or common names)
    /// of `region`, each with the five equations growth needs.
    pub fn species(&self, db: &Database, region: &str) -> Result<Vec<Measured>, ApiError> {
        let allowed = "1 to 4 species of the region, comma-separated: codes (PLAC), scientific \
                       or common names (see /api/species?region=...)";
        let given = self
            .0
            .get("species")
            .map(|s| s.trim())
            .filter(|s| !s.is_empty())
            .ok_or_else(|| ApiError::bad("species", "required".into(), allowed))?;
        let names: Vec<&str> = given.split(',').map(str::trim).collect();
        if names.len() > MAX_SPECIES {
            return Err(ApiError::bad(
                "species",
                format!("{} species given, at most {MAX_SPECIES}", names.len()),
                allowed,
            ));
        }
        names
            .iter()
            .map(|n| {
                db.find(region, n)
                    .map_err(|e| ApiError::bad("species", e.to_string(), allowed))
            })
            .collect()
    }

    /// Exactly one species; `what` says why one (`"a GLB holds one tree"`).
    pub fn one_species(
        &self,
        db: &Database,
        region: &str,
        what: &str,
    ) -> Result<Measured, ApiError> {
        let mut species = self.species(db, region)?;
        if species.len() != 1 {
            return Err(ApiError::bad(
                "species",
                format!("{} species given; {what}", species.len()),
                "one species",
            ));
        }
        Ok(species.remove(0))
    }

    /// A whole age the data of every species in `species` cover.
    pub fn age(&self, species: &[Measured]) -> Result<u32, ApiError> {
        let (lo, hi) = species.iter().fold((1u32, u32::MAX), |(lo, hi), m| {
            let ages = crate::grown::ages_of(m);
            (
                lo.max(ages.first().copied().unwrap_or(1)),
                hi.min(ages.last().copied().unwrap_or(0)),
            )
        });
        let allowed = format!("a whole number of years from {lo} to {hi}");
        let given = self
            .0
            .get("age")
            .ok_or_else(|| ApiError::bad("age", "required".into(), allowed.clone()))?;
        let age: f64 = given.trim().parse().map_err(|_| {
            ApiError::bad("age", format!("`{given}` is not a number"), allowed.clone())
        })?;
        if !(age.fract() == 0.0 && age >= f64::from(lo) && age <= f64::from(hi)) {
            let names: Vec<String> = species.iter().map(|m| m.label()).collect();
            return Err(ApiError::bad(
                "age",
                format!("{age} is outside the data for {}", names.join(", ")),
                allowed,
            ));
        }
        Ok(age as u32)
    }

    /// The seed (default 0).
    pub fn seed(&self) -> Result<u64, ApiError> {
        match self.0.get("seed") {
            None => Ok(0),
            Some(s) => s.trim().parse().map_err(|_| {
                ApiError::bad(
                    "seed",
                    format!("`{s}` is not a whole number"),
                    "a whole number from 0 to 18446744073709551615",
                )
            }),
        }
    }

    /// The site's index in [`crate::grown::sites`] (default `narrow`).
    pub fn site(&self) -> Result<usize, ApiError> {
        let given = self.0.get("site").map_or("narrow", String::as_str);
        crate::grown::site_index(given).ok_or_else(|| {
            let keys: Vec<&str> = crate::grown::sites().iter().map(|s| s.key).collect();
            ApiError::bad(
                "site",
                format!("`{given}` is not a built-in site"),
                keys.join(", "),
            )
        })
    }

    /// The site whose pruning regime cuts the tree: `pruning=on` with a site (its index in
    /// [`crate::grown::sites`]); none with `pruning=off`, the default: the tree is never cut.
    pub fn pruned(&self) -> Result<Option<usize>, ApiError> {
        match self.0.get("pruning").map(String::as_str) {
            None | Some("off") => Ok(None),
            Some("on") => Ok(Some(self.site()?)),
            Some(other) => Err(ApiError::bad(
                "pruning",
                format!("`{other}` is not a choice"),
                "on (the site's pruning regime cuts the tree), off (never cut)",
            )),
        }
    }

    /// The detail level of a tree for the page (default 0, the whole tree; the last, the leaf shell).
    pub fn detail(&self) -> Result<u32, ApiError> {
        let top = crate::grown::DETAIL_LEVELS - 1;
        let allowed = format!("a whole number from 0 (every twig and leaf) to {top} (coarsest)");
        match self.0.get("detail") {
            None => Ok(0),
            Some(s) => match s.trim().parse::<u32>() {
                Ok(d) if d <= top => Ok(d),
                _ => Err(ApiError::bad(
                    "detail",
                    format!("`{s}` is not a detail level"),
                    allowed,
                )),
            },
        }
    }

    /// A picture size `WxH` (default 1280x720), each side 64 to 4096 pixels.
    pub fn size(&self) -> Result<(u32, u32), ApiError> {
        let given = self.0.get("size").map_or("1280x720", String::as_str);
        let allowed = "WIDTHxHEIGHT, each 64 to 4096 pixels";
        let parsed = given
            .split_once('x')
            .and_then(|(w, h)| Some((w.trim().parse().ok()?, h.trim().parse().ok()?)));
        match parsed {
            Some((w, h)) if (64..=4096).contains(&w) && (64..=4096).contains(&h) => Ok((w, h)),
            _ => Err(ApiError::bad(
                "size",
                format!("`{given}` is not a picture size"),
                allowed,
            )),
        }
    }
}
