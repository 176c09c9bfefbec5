"""The dry-joint corner block by block: one specimen description (specimen.py) for the
drawings (draw.py), a rigid-block limit analysis of the assembly as a linear program
(assembly.py, lp.py) and a DEM tilting test in LMGC90 (dem.py). docs/corner-blocks.md."""
