; Strand scaffold (toolpaths for Direct Ink Writing)
; machine: deltawasp-2040-clay-valve, firmware marlin, deposition valve, arcs as G1 chords within 0.01 mm
; units: mm, mm/min
; param angles = 0,90
; param gap = 1.6
; param layers = 2
; param nozzle = 0.84
; param size = 5,5
; param speed = 250
; param arc-tolerance = 0.01
; derived bead_area_mm2 = 0.5037
; derived filaments_per_layer = 3,3
; derived footprint_mm = 5.72,5.72
; derived gap_mm = 1.6000
; derived height_mm = 1.4784
; derived layer_height_mm = 0.7392
; derived layers = 2
; derived link_clearance_mm = 2.4400
; derived overhang_mm = 0.8400
; derived pitch_mm = 2.4400
; derived porosity = 0.6426
; derived porosity_formula = 1 - (filament length inside the footprint * bead area) / (width * depth * height)
; estimate layers = 2
; estimate deposit_length_mm = 66.44
; estimate travel_length_mm = 1.739
; estimate ink_volume_ml = 0.0335
; estimate reservoir_ml = 30
; estimate syringe_fills = 0.001
; estimate syringe_loads = 1
; estimate time_naive_s = 17.1
; estimate time_trapezoid_s = 17.2
; layer 0: length 27.08 mm, ink 0.01364 mL, time 7.13 s (naive 7.1 s)
; layer 1: length 39.36 mm, ink 0.01982 mL, time 10.05 s (naive 10.02 s)
;
M107 ; fan off
G28 ; home (delta: to the top)
M42 P6 S0 ; air valve closed
M106 S10 ; drying air on (thesis)
G21 ; millimetres
G90 ; absolute XYZ
;LAYER_CHANGE
;Z:0.739
;HEIGHT:0.739
;LAYER:0
G0 X-3.700 Y-2.440 Z1.739 F1500
G0 Z0.739 F600
M400
M42 P6 S255 ; air valve open
G4 P500
;TYPE:Solid infill
;FEATURE:infill
;WIDTH:0.840
G1 X3.700 F250
G1 X1.5 Ynan
G2 X2 Y2
G3 X2.5 Y2 I1e9 J0
G2 X3 Y2 I0.25 J0
G1 X900 Y0
G1 X3 Y2
G1 Y0.000
G1 X-3.700
G1 Y2.440
G1 X2.450
M400
M42 P6 S0 ; air valve closed
G1 X3.700
;LAYER_CHANGE
;Z:1.478
;HEIGHT:0.739
;LAYER:1
G0 Z1.478 F600
M400
M42 P6 S255 ; air valve open
G4 P500
;TYPE:Skirt/Brim
;FEATURE:link
G1 X6.140 F250
G1 Y6.140
G1 X2.440
G1 Y3.700
;TYPE:Solid infill
;FEATURE:infill
G1 Y-3.700
G1 X0.000
G1 Y3.700
G1 X-2.440
G1 Y-2.450
M400
M42 P6 S0 ; air valve closed
G1 Y-3.700
;TYPE:Custom
M400
M42 P6 S0 ; air valve closed
M107 ; drying air off
G28 ; home (delta: to the top, clear of the part)
