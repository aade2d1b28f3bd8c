; A drawing lifted by Z only: no pen command, no E. Strokes cross (drawing content).
G21
G90
G0 Z5
G0 X0 Y0
G1 Z0 F300
G1 X20 Y20 F1200
G1 Z5
G0 X0 Y20
G1 Z0
G1 X20 Y0
G1 X20 Y-5
G1 Z5
G0 X30 Y30
