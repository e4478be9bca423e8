"""MeltDEM's command-line tool (`meltdem`): cli (argparse), examples, check, run, progress,
foamdict / lammps_input (readers), post (post-processing: VTK series, plots, summary)."""
