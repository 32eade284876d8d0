// The city view's report panel: the first epoch beside the one shown, and the condition the
// inventory recorded with each species' relative performance, as the city's report
// (`sylva city --report`, report.json) gives them.

/** Text made safe to put inside HTML. */
export const esc = (s) => String(s ?? '').replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' })[c]);

/** The report `r`'s first epoch and the one `years` after the inventory, as an HTML table. */
export function epochTable(r, years) {
  const epochs = r.epochs || [];
  const first = epochs[0];
  const now = epochs.find((e) => e.years === years) || first;
  const cell = (e, k, d = 0) => {
    if (!e) return '–';
    const v = k === 'expected_alive_share' ? 100 * e[k] : e[k];
    return Number(v).toLocaleString(undefined, { maximumFractionDigits: k === 'expected_alive_share' ? 1 : d });
  };
  const rows = [['Trees', 'trees'], ['Canopy, m²', 'canopy_m2'], ['Leaf area, m²', 'leaf_area_m2'],
    ['Benefits (Sylva: four of five categories, energy not computed), $/yr', 'benefits_usd'],
    ['Benefits (i-Tree typical), $/yr', 'typical_total_usd'],
    ['Trees expected standing, %', 'expected_alive_share'],
    ['Benefits (Sylva), expected, $/yr', 'expected_benefits_usd']];
  // The first epoch, and the one shown beside it.
  const later = now !== first;
  const name = (e) => (e.years === 0 ? 'as inventoried' : `+${e.years} years`);
  return `<table id="report-epochs"><tr><th></th><th>${first ? name(first) : ''}</th>` +
    (later ? `<th>${name(now)}</th>` : '') + '</tr>' +
    rows.map(([label, k]) => `<tr><th>${label}</th><td data-k="${k}" data-first>${cell(first, k)}</td>` +
      (later ? `<td data-k="${k}">${cell(now, k)}</td>` : '') + '</tr>').join('') + '</table>' +
    (r.flags?.length ? `<p class="note">Flagged: ${r.flags.map(esc).join('; ')}</p>` : '') +
    conditionLine(r);
}

/** The condition the inventory recorded, and the species that do best and worst by i-Tree
 * Streets' relative performance index (a species' share in good condition over the city's). */
export function conditionLine(r) {
  const o = r.observed;
  const [g, f, p] = o?.good_fair_poor || [0, 0, 0];
  const n = g + f + p;
  if (!n) return '<p id="report-condition" class="note">Condition: not recorded in the inventory.</p>';
  const pct = (k) => `${Math.round((100 * k) / n)}%`;
  const name = (code) => esc(r.species.find((s) => s.code === code)?.common || code);
  const ranked = o.condition.filter((c) => c.rpi !== null).sort((a, b) => b.rpi - a.rpi);
  const list = (cs) => cs.map((c) => `${name(c.code)} ${c.rpi.toFixed(2)}`).join(', ');
  return `<p id="report-condition">Condition as recorded (${n} trees${o.not_recorded ? `, ${o.not_recorded} not recorded` : ''}): ` +
    `${pct(g)} good, ${pct(f)} fair, ${pct(p)} poor. Relative performance (1: the city's trees), best: ` +
    `${list(ranked.slice(0, 3))}; worst: ${list(ranked.slice(-3).reverse())}.</p>`;
}
