"""The laboratory's peak (and another simulation's) on a stress-strain plot, from the "reference"
entry of a shear test's summary.json, which a run writes only when its config has
[test.laboratory]: without it nothing is drawn."""


def draw_laboratory(ax, ref):
    if not ref:
        return
    source = ref.get("source", "laboratory")
    peak = 1e-3 * ref["laboratory_peak_axial_stress_Pa"]
    if "laboratory_axial_strain_at_peak" in ref:
        strain = 100 * ref["laboratory_axial_strain_at_peak"]
        ax.plot([strain], [peak], "ks", label=f"{source}: peak {peak:.2f} kPa at {strain:.2f} %")
    else:
        ax.axhline(peak, color="k", ls="--", lw=0.8, label=f"{source}: peak {peak:.2f} kPa")
    if "published_dem_peak_axial_stress_Pa" in ref:
        dem = 1e-3 * ref["published_dem_peak_axial_stress_Pa"]
        ax.axhline(dem, color="gray", ls=":", label=f"published DEM peak ({dem:.2f} kPa)")
