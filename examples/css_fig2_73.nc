%
O0273 (MANUAL FIGURE 2.73: CONSTANT SURFACE SPEED 300 M/MIN)
(SPINDLE 955 R/MIN AT A, 1910 AT B AND ALONG B-C, 1910 TO 1194 ALONG C-D)
M3 G96 S300
G0 X100 Z100                     (A)
G0 X50 Z0                        (B)
G1 W-30 F200                     (C)
X80 W-20 F150                    (D)
G0 X100 Z100                     (A)
M30
%
