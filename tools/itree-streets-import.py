#!/usr/bin/env python3
"""Writes crates/sylva/data/itree-streets/ from i-Tree Streets' resource-unit tables as
OpenTreeMap's otm-ecoservice ships them (data/output__<REGION>__<factor>.csv and
data/output__<REGION>__species_codes.csv).

    git -C otm-ecoservice archive HEAD data | tar -x -C /tmp/otm
    tools/itree-streets-import.py /tmp/otm/data <commit>

Each source table has the nine DBH class midpoints (cm) as its header and one row per i-Tree
species code, then, in some files, notes and blank rows: a table ends at its first row with no
code. The values are written as published (text, not reparsed); an empty cell stays empty
(the value is missing, not zero). One file per region, long form: factor, code, nine values.
"""
import csv
import os
import sys

# The factors Sylva reads: the fifteen otm-ecoservice's service computes, then leaf surface area
# and the yearly property-value figure that i-Tree Streets' aesthetics benefit is priced from.
FACTORS = [
    "electricity", "natural_gas", "hydro_interception", "co2_sequestered", "co2_avoided",
    "co2_storage", "aq_ozone_dep", "aq_nox_dep", "aq_pm10_dep", "aq_sox_dep", "aq_nox_avoided",
    "aq_pm10_avoided", "aq_sox_avoided", "aq_voc_avoided", "bvoc", "property_value", "lsa",
]
# otm-ecoservice's region codes (climate zone and reference city) and the short names Sylva's
# region tables use (the same as the Urban Tree Database's).
REGIONS = {
    "CaNCCoJBK": "NoCalC", "CenFlaXXX": "CenFla", "GulfCoCHS": "GulfCo", "InlEmpCLM": "InlEmp",
    "InlValMOD": "InlVal", "InterWABQ": "InterW", "LoMidWXXX": "LoMidW", "MidWstMSP": "MidWst",
    "NMtnPrFNL": "NMtnPr", "NoEastXXX": "NoEast", "PacfNWLOG": "PacfNW", "PiedmtCLT": "Piedmt",
    "SWDsrtGDL": "SWDsrt", "SoCalCSMA": "SoCalC", "TpIntWBOI": "TpIntW", "TropicPacXXX": "Tropic",
}
BREAKS = ["3.81", "11.43", "22.86", "38.10", "53.34", "68.58", "83.82", "99.06", "114.30"]


def rows(path):
    with open(path, newline="", encoding="latin-1") as f:
        return list(csv.reader(f))


def table(path):
    body = rows(path)
    if [c.strip() for c in body[0][1:10]] != BREAKS:
        sys.exit(f"{path}: DBH classes {body[0][1:10]}, expected {BREAKS}")
    out = []
    for r in body[1:]:
        if not r or not r[0].strip():
            break
        values = [c.strip() for c in (r[1:10] + [""] * 9)[:9]]
        for v in values:
            if v:
                float(v)  # a value that is not a number stops the import
        out.append((r[0].strip(), values))
    return out


def main():
    src, commit = sys.argv[1], sys.argv[2]
    dest = os.path.join(os.path.dirname(__file__), "..", "crates", "sylva", "data", "itree-streets")
    os.makedirs(dest, exist_ok=True)
    species = []
    for code, short in sorted(REGIONS.items(), key=lambda kv: kv[1]):
        with open(os.path.join(dest, f"{short}.csv"), "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(["factor", "code"] + BREAKS)
            for factor in FACTORS:
                for name, values in table(os.path.join(src, f"output__{code}__{factor}.csv")):
                    w.writerow([factor, name] + values)
        for r in rows(os.path.join(src, f"output__{code}__species_codes.csv"))[1:]:
            if r and r[0].strip():
                species.append([short] + [c.strip() for c in r[:5]])
    with open(os.path.join(dest, "species.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["region", "code", "scientific_name", "common_name", "tree_type", "values_from"])
        w.writerows(species)
    print(f"wrote {len(REGIONS)} regions and {len(species)} species rows from otm-ecoservice {commit}")


main()
