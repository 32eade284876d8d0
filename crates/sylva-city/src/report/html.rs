//! The city's report as a page of HTML tables (`CityReport::html`).

use crate::report::published::Comparison;
use crate::report::{CityReport, observed, pavement, predicted};
use crate::trees::benefits::CATEGORIES;
use std::fmt::Write as _;
use sylva::growth::DBH_CLASS_EDGES_CM;

/// `s` safe in HTML text.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl CityReport {
    /// As a page of HTML tables.
    pub fn html(&self) -> String {
        let money = |v: Option<f64>| v.map_or("–".to_string(), |v| format!("${v:.0}"));
        let mut h = String::from(
            "<!doctype html><meta charset=\"utf-8\"><title>Sylva: the city's trees</title>\
             <style>body{font:14px system-ui,sans-serif;margin:2em}table{border-collapse:\
             collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}\
             td:first-child,th:first-child{text-align:left}td+td{white-space:nowrap}.flag{color:#a33}\
             </style>\n",
        );
        let _ = writeln!(h, "<h1>The city's trees</h1><p>{} trees.</p>", self.trees);
        for f in &self.flags {
            let _ = writeln!(h, "<p class=\"flag\">{}</p>", esc(f));
        }
        h.push_str(
            "<h2>Composition, size and benefits by species</h2><table><tr><th>Species</th>\
             <th>Trees</th><th>Share</th><th>Importance</th><th>Leaf area m²</th>\
             <th>DBH classes, cm (&lt;7.6 … ≥106.7): relative age as i-Tree Streets shows it</th>\
             <th>Estimated age (years: &lt;10 · 10–20 · 20–40 · 40–60 · ≥60)</th>\
             <th>Mean age</th><th>At the data's oldest</th><th>Sylva $/yr (four categories; \
             energy not computed)</th><th>i-Tree typical $/yr</th></tr>\n",
        );
        for s in &self.species {
            let classes: Vec<String> = s.dbh_classes.iter().map(|n| n.to_string()).collect();
            let ages: Vec<String> = s.age_classes.iter().map(|n| n.to_string()).collect();
            let _ = writeln!(
                h,
                "<tr><td>{} <i>{}</i> ({})</td><td>{}</td><td>{:.1}%</td><td>{:.1}</td>\
                 <td>{:.0}</td><td>{}</td><td>{}</td><td>{:.0}</td><td>{}</td><td>{}</td>\
                 <td>{}</td></tr>",
                esc(&s.common),
                esc(&s.scientific),
                esc(&s.code),
                s.trees,
                100.0 * s.share,
                s.importance,
                s.leaf_area_m2,
                classes.join(" · "),
                ages.join(" · "),
                s.mean_age_years,
                s.at_oldest_measured,
                money(s.benefits_usd),
                money(s.typical_total_usd)
            );
        }
        h.push_str("</table>\n");
        self.observed_html(&mut h, &esc);
        self.categories_html(&mut h);
        shares_html(&mut h, "Genera", "Genus", &self.genera, true, &esc);
        shares_html(&mut h, "Families", "Family", &self.families, false, &esc);
        h.push_str(
            "<h2>The city over the years</h2><table><tr><th>Years on</th><th>Trees</th>\
             <th>Canopy m²</th><th>Leaf area m²</th><th>Sylva $/yr</th><th>i-Tree typical $/yr</th>\
             <th>Expected standing</th><th>Sylva $/yr, expected</th></tr>\n",
        );
        for e in &self.epochs {
            let _ = writeln!(
                h,
                "<tr><td>{}</td><td>{}</td><td>{:.0}</td><td>{:.0}</td><td>${:.0}</td><td>${:.0}</td>\
                 <td>{:.1}%</td><td>${:.0}</td></tr>",
                e.years,
                e.trees,
                e.canopy_m2,
                e.leaf_area_m2,
                e.benefits_usd,
                e.typical_total_usd,
                100.0 * e.expected_alive_share,
                e.expected_benefits_usd
            );
        }
        h.push_str("</table>\n");
        if let Some(c) = &self.published {
            comparison_html(&mut h, c, &esc);
        }
        h.push_str("<h2>Models</h2><ul>\n");
        for m in &self.models {
            let _ = writeln!(h, "<li>{}</li>", esc(m));
        }
        h.push_str("</ul><h2>Not computed</h2><ul>\n");
        for m in &self.not_computed {
            let _ = writeln!(h, "<li>{}</li>", esc(m));
        }
        h.push_str("</ul>\n");
        h
    }
}

impl CityReport {
    /// Condition and relative performance by species, and the problems the surveyors saw, by
    /// species and DBH class; or that the inventory records none.
    fn observed_html(&self, h: &mut String, esc: &dyn Fn(&str) -> String) {
        let o = &self.observed;
        let name = |code: &str| {
            self.species
                .iter()
                .find(|s| s.code == code)
                .map_or(esc(code), |s| {
                    format!(
                        "{} <i>{}</i> ({})",
                        esc(&s.common),
                        esc(&s.scientific),
                        esc(code)
                    )
                })
        };
        h.push_str("<h2>Condition and relative performance, as the inventory recorded them</h2>\n");
        if !o.has_condition() {
            h.push_str(
                "<p>The inventory records no condition (no <code>health</code> or \
                 <code>condition</code> column, or none Sylva could read; name one with \
                 <code>--condition-col</code>).</p>\n",
            );
        } else {
            let pct = |n: usize, of: usize| format!("{:.0}%", 100.0 * n as f64 / of.max(1) as f64);
            h.push_str(
                "<p>Shares of the trees whose condition was recorded. The relative performance \
                 index (i-Tree Streets) is a species' share in good condition over the city's: \
                 above 1 it does better than the city's trees, below 1 worse.</p><table><tr>\
                 <th>Species</th><th>Recorded</th><th>Good</th><th>Fair</th><th>Poor</th>\
                 <th>Not recorded</th><th>RPI</th><th>Reading</th></tr>\n",
            );
            let all: usize = o.good_fair_poor.iter().sum();
            for r in &o.condition {
                let n: usize = r.good_fair_poor.iter().sum();
                let [g, f, p] = r.good_fair_poor;
                let _ = writeln!(
                    h,
                    "<tr><td>{}</td><td>{n}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
                     <td>{}</td><td>{}</td></tr>",
                    name(&r.code),
                    pct(g, n),
                    pct(f, n),
                    pct(p, n),
                    r.not_recorded,
                    r.rpi.map_or("–".into(), |v| format!("{v:.2}")),
                    observed::reading(r.rpi)
                );
            }
            let [g, f, p] = o.good_fair_poor;
            let _ = writeln!(
                h,
                "<tr><th>All</th><th>{all}</th><th>{}</th><th>{}</th><th>{}</th><th>{}</th>\
                 <th>1.00</th><th></th></tr></table>",
                pct(g, all),
                pct(f, all),
                pct(p, all),
                o.not_recorded
            );
        }
        if !o.unread.is_empty() {
            h.push_str("<p>Values Sylva could not place, counted as not recorded:</p><ul>\n");
            for (column, value, n) in &o.unread {
                let rows = if *n == 1 { "row" } else { "rows" };
                let _ = writeln!(
                    h,
                    "<li><code>{}</code> = “{}”: {n} {rows}</li>",
                    esc(column),
                    esc(value)
                );
            }
            h.push_str("</ul>\n");
        }
        if o.problems.is_empty() {
            return;
        }
        h.push_str(
            "<h2>The street's problems, as the inventory recorded them</h2><p>Shares of the \
             trees for which each was recorded, by species and DBH class.</p><table><tr>\
             <th>Species</th><th>DBH class, cm</th><th>Trees</th><th>Sidewalk damaged</th>\
             <th>Lights or wires in the branches</th><th>Wire or lights on the trunk</th>\
             <th>Paving or grate on the roots</th></tr>\n",
        );
        let share = |s: &observed::Seen| {
            s.share()
                .map_or("–".into(), |v| format!("{:.0}%", 100.0 * v))
        };
        for p in &o.problems {
            let _ = writeln!(
                h,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                name(&p.code),
                dbh_class_words(p.dbh_class),
                p.trees,
                share(&p.sidewalk_damage),
                share(&p.branch_lights),
                share(&p.trunk_wire_or_lights),
                share(&p.root_paving)
            );
        }
        h.push_str("</table>\n");
        self.predicted_html(h, &name);
    }

    /// Sylva's site model on a typical street beside what was recorded: each species' first
    /// age in the lines' clearance, and the shares of its trees under and over that DBH with
    /// lights or wires in the branches.
    fn predicted_html(&self, h: &mut String, name: &dyn Fn(&str) -> String) {
        self.pavement_html(h);
        if self.predicted.is_empty() {
            return;
        }
        let _ = writeln!(
            h,
            "<h3>Lines: beside Sylva's site model on a typical street</h3><p>Each species as \
             grown for the city, unpruned, set on <code>{}</code> (a 1.2 m strip between curb \
             and sidewalk, a line overhead at 8.5 m): the first age class whose crown enters \
             the line's clearance, with the DBH the equations give then; beside it, the \
             recorded shares of its trees under and at or over that DBH with lights or wires \
             in the branches. The events differ: the census's lights or wires in the branches \
             are mostly string lights and wires hung in the tree, not the utility lines the \
             site model clears, so they follow the street's decorations more than the crown's \
             reach.</p><table><tr><th>Species</th><th>Crown into the line's clearance</th>\
             <th>Lights or wires in the branches, under · at or over</th></tr>",
            predicted::SITE.0
        );
        // A crown that grows into the line's clearance needs the utility's crews for life:
        // the ranking (`sylva rank --site`) prices it, and says it does not suit such a site
        // where the crews must come back between cycles.
        let when = |f: Option<predicted::First>, years: f64| {
            f.map_or(
                format!("not by {years:.0} years (its oldest class): suits a street under lines"),
                |f| {
                    format!(
                        "DBH {:.0} cm (age {:.0}): needs the utility's crews under lines \
                         (<code>sylva rank --site</code> prices them)",
                        f.dbh_cm, f.age
                    )
                },
            )
        };
        for p in &self.predicted {
            let rows: Vec<&observed::ProblemRow> = (self.observed.problems.iter())
                .filter(|r| r.code == p.code)
                .collect();
            // The shares recorded in the DBH classes below the predicted DBH's, and from it up.
            let split =
                |f: Option<predicted::First>,
                 seen: &dyn Fn(&observed::ProblemRow) -> observed::Seen| {
                    let k = f.map_or(usize::MAX, |f| {
                        DBH_CLASS_EDGES_CM.partition_point(|&e| e <= f.dbh_cm)
                    });
                    let sum = |under: bool| {
                        let mut s = observed::Seen::default();
                        for r in rows.iter().filter(|r| (r.dbh_class < k) == under) {
                            let v = seen(r);
                            s.recorded += v.recorded;
                            s.with += v.with;
                        }
                        s.share().map_or("–".into(), |v| {
                            format!("{:.0}% of {}", 100.0 * v, s.recorded)
                        })
                    };
                    format!("{} · {}", sum(true), sum(false))
                };
            let _ = writeln!(
                h,
                "<tr><td>{}</td><td>{}</td><td>{}</td></tr>",
                name(&p.code),
                when(p.wire, p.years),
                split(p.wire, &|r| r.branch_lights)
            );
        }
        h.push_str("</table>\n");
    }

    /// Sylva's roots model beside the sidewalk damage recorded: by DBH class, by place
    /// against the curb and by species, each difference past 10 points marked, with whether
    /// the class's sampling error covers it.
    fn pavement_html(&self, h: &mut String) {
        let Some(p) = &self.pavement else { return };
        let _ = writeln!(
            h,
            "<h3>Sidewalk damage: recorded beside Sylva's roots model</h3><p>Each tree \
             standing with its sidewalk recorded is given the share of such trees the roots \
             model finds beside a damaged flag (<code>sylva::street::work::roots</code>: fitted \
             to New York's 2015 Street Tree Census, by the tree's DBH, its bed's place against \
             the curb, read as along it where not recorded, and its species' rooting habit, \
             its own, its genus's or the census's mean); the shares are set beside the \
             recorded ones. A difference past {:.0} points is marked, and said to lie within \
             the class's sampling error (two standard errors of its trees' share) where it \
             does.</p>",
            100.0 * pavement::EXPLAINED_PAST
        );
        let table = |h: &mut String, title: &str, rows: &[(&pavement::Class, Option<&str>)]| {
            let _ = writeln!(
                h,
                "<table><tr><th>{title}</th><th>Trees recorded</th><th>Recorded damaged</th>\
                 <th>Roots model</th><th>Difference</th></tr>"
            );
            for (c, habit) in rows {
                let d = c.difference();
                let mark = if d.abs() > pavement::EXPLAINED_PAST {
                    c.sampling()
                        .unwrap_or_else(|| "past the sampling error".into())
                } else {
                    String::new()
                };
                let _ = writeln!(
                    h,
                    "<tr><td>{}{}</td><td>{}</td><td>{:.1}%</td><td>{:.1}%</td>\
                     <td>{:+.1} points{}</td></tr>",
                    esc(&c.class),
                    habit.map_or(String::new(), |h| format!(" <small>(rooting: {h})</small>")),
                    c.trees,
                    100.0 * c.observed,
                    100.0 * c.predicted,
                    100.0 * d,
                    if mark.is_empty() {
                        String::new()
                    } else {
                        format!(" <small>{}</small>", esc(&mark))
                    }
                );
            }
            h.push_str("</table>\n");
        };
        let mut first = vec![(&p.all, None)];
        first.extend(p.by_place.iter().map(|c| (c, None)));
        table(h, "Place against the curb", &first);
        let dbh: Vec<_> = p.by_dbh.iter().map(|c| (c, None)).collect();
        table(h, "DBH class", &dbh);
        let species: Vec<_> = (p.by_species.iter())
            .map(|(c, habit)| (c, Some(habit.as_str())))
            .collect();
        table(h, "Species", &species);
    }

    /// Benefits per tree at the first epoch by category, Sylva's own beside i-Tree's typical
    /// position: every category present, a missing one said to be not computed.
    fn categories_html(&self, h: &mut String) {
        h.push_str(
            "<h2>Benefits per tree by category</h2><table><tr><th>$ a tree a year</th>\
             <th>Sylva (the grown crowns)</th><th>i-Tree typical position</th></tr>\n",
        );
        let money = |v: Option<f64>| {
            v.map_or("not computed (an inventory has no façades)".into(), |v| {
                format!("${v:.2}")
            })
        };
        for (k, c) in CATEGORIES.iter().enumerate() {
            let _ = writeln!(
                h,
                "<tr><td>{}</td><td>{}</td><td>{}</td></tr>",
                c.replace('_', " "),
                money(self.own_per_tree_usd[k]),
                money(self.typical_per_tree_usd[k])
            );
        }
        let sum = |v: &[Option<f64>]| v.iter().flatten().sum::<f64>();
        let _ = writeln!(
            h,
            "<tr><td>Sylva: the four computed; i-Tree: all five</td><td>${:.2}</td><td>${:.2}</td></tr></table>",
            sum(&self.own_per_tree_usd),
            sum(&self.typical_per_tree_usd)
        );
    }
}

/// A table of names (genera in italics) with their trees and share of the city's.
fn shares_html(
    h: &mut String,
    title: &str,
    heading: &str,
    rows: &[(String, usize, f64)],
    italic: bool,
    esc: &dyn Fn(&str) -> String,
) {
    let _ = writeln!(
        h,
        "<h2>{title}</h2><table><tr><th>{heading}</th><th>Trees</th><th>Share</th></tr>"
    );
    for (name, n, share) in rows {
        let name = if italic {
            format!("<i>{}</i>", esc(name))
        } else {
            esc(name)
        };
        let _ = writeln!(
            h,
            "<tr><td>{name}</td><td>{n}</td><td>{:.1}%</td></tr>",
            100.0 * share
        );
    }
    h.push_str("</table>\n");
}

/// The section that sets this city's benefits per tree beside a published city's.
fn comparison_html(h: &mut String, c: &Comparison, esc: &dyn Fn(&str) -> String) {
    let p = &c.published;
    let _ = writeln!(
        h,
        "<h2 id=\"published\">Benefits per tree beside {}'s</h2><p>This city at the first \
         epoch (i-Tree Streets' typical position at each tree's DBH) beside {}'s {} trees as \
         published: {}.</p><table><tr><th>$ a tree a year</th><th>This city</th><th>{} {}</th>\
         <th>Ratio</th></tr>",
        esc(&p.city),
        esc(&p.city),
        p.trees,
        esc(p.source.trim_end_matches('.')),
        esc(&p.city),
        p.year
    );
    let money = |v: Option<f64>| v.map_or("not computed".to_string(), |v| format!("${v:.2}"));
    for (category, ours, theirs) in &c.rows {
        let ratio = match (ours, theirs) {
            (Some(a), Some(b)) if *b > 0.0 => format!("{:.2}", a / b),
            _ => "–".into(),
        };
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{ratio}</td></tr>",
            category.replace('_', " "),
            money(*ours),
            money(*theirs)
        );
    }
    h.push_str("</table><p>Why they differ:</p><ul>\n");
    for d in &c.differences {
        let _ = writeln!(h, "<li>{}</li>", esc(d));
    }
    h.push_str("</ul>\n");
}

/// DBH class `k` (of i-Tree's nine) in centimetres, as HTML: "&lt;7.6", "15.2–30.5", "≥106.7".
fn dbh_class_words(k: usize) -> String {
    let edges = DBH_CLASS_EDGES_CM;
    match k {
        0 => format!("&lt;{:.1}", edges[0]),
        k if k >= edges.len() => format!("≥{:.1}", edges[edges.len() - 1]),
        k => format!("{:.1}–{:.1}", edges[k - 1], edges[k]),
    }
}
