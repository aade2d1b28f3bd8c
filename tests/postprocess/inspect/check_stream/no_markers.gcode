; No layer comments: layers start where a deposit changes z. Relative XYZ for a while,
; G92 resets, a dwell before the first move, absolute E.
G21
G4 S1
G90
M82
G92 E0
G0 X0 Y0 Z0.3 F3000
G1 X10 Y0 E1 F600
G1 X10 Y10 E2
G1 X0 Y0 E3
G1 X10 Y5 E4
G0 Z0.6
G1 X0 Y5 E5
G91
G1 X5 Y5 E1
G1 X-5 Y-5 E1
G90
G1 X10 Y10 Z0.9 E8
G1 X0 Y10 E9
G1 X10 Y0 E10
G92 X0 Y0
G1 X5 Y5 E11
G0 Z5
