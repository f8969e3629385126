(work offsets from the setup, inch input)
G21 G90 G54 G00 X0 Y0 Z10.
G55 X0 Y0
G20 G01 X1. Y-0.5 Z0 F10.
G21 G91 G00 X-5.
G90 G54 Z0
M02
G00 X99. (after the end: not run)
