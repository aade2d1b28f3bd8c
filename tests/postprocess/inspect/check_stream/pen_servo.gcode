; A drawing with a servo pen (M300): read as plot rules without a machine.
G21
G90
G0 X0 Y0
M300 S30
G1 X20 Y20 F1200
M300 S50
G0 X0 Y20
M300 S30
G1 X20 Y0
G1 X21 Y0
M300 S50
G0 X0 Y0
