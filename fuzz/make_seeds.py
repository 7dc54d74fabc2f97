#!/usr/bin/env python3
"""Writes the hand-made seed corpus (fuzz/corpus/*/seed_*). Run from fuzz/.
Examples are copied from ../examples; the worked programs are those of seed 003
(the FANUC-0TJ textbook chapter); the rest are edge cases."""
import glob, os, random, shutil

def put(target, name, data):
    if isinstance(data, str):
        data = data.encode()
    with open(f"corpus/{target}/seed_{name}", "wb") as f:
        f.write(data)
    if target == "program":
        # The parser target reads the same text after its number-format byte.
        with open(f"corpus/parser/seed_{name}", "wb") as f:
            f.write(b"\0" + data)

for p in sorted(glob.glob("../examples/**/*.nc", recursive=True)):
    put("program", "ex_" + os.path.basename(p)[:-3], open(p, "rb").read())

SEED003 = {
 "g71_g70": "O0001\nN10 G50 X200 Z140 T0101\nN20 G90 G40 G97 G99 S240 M03\nN30 G00 G42 X120 Z12 M08\nN40 G96 S120\nN50 G71 U2 R0.1\nN60 G71 P70 Q130 U2 W2 F0.3\nN70 G00 X40\nN80 G01 Z-30 F0.15 S150\nN90 X60 Z-60\nN100 Z-80\nN110 X100 Z-90\nN120 Z-110\nN130 X120 Z-130\nN135 G70 P70 Q130\nN140 G00 X125 G40\nN150 X200 Z140\nN160 M02\n",
 "g73_g70": "N10 G50 X200 Z200 T0101\nN20 G97 G40 S200 M03\nN30 G00 G42 X140 Z40 M08\nN40 G96 S120\nN50 G73 U9.5 W9.5 R3\nN60 G73 P70 Q130 U1.0 W0.5 F0.3\nN70 G00 X20 Z0\nN80 G01 Z-20 F0.15 S150\nN90 X40 Z-30\nN100 Z-50\nN110 G02 X80 Z-70 R20\nN120 G01 X100 Z-80\nN130 X105\nN140 G70 P70 Q130\nN145 G00 X200 Z200 G40\nN150 M02\n",
 "g75": "N10 G50 X200 Z200 T0505\nN20 G97 S700 M03\nN30 G00 G40 X35 Z-50 M08\nN40 G96 S80\nN50 G75 R1\nN60 G75 X-1 P5 F0.15\nN70 G00 X200 Z200 T0500\nN80 M02\n",
 "g32": "G50 X100 Z100\nG97 S300 M03\nG00 X70 Z80\nN100 G00 U-62\nN110 G32 W-74.5 F4\nN130 G00 U62\nN140 W74.5\nN150 U-64\nN160 G32 W-74.5\nN170 G00 U64\nN180 W74.5\nM30\n",
 "g92": "N50 G50 X270 Z260\nN60 G97 S300\nN70 T0101 M03\nN80 G00 X35 Z104\nN90 G92 X29.2 Z56 F1.5\nN100 X28.6\nN110 X28.2\nN120 X28.04\nN130 G00 X270 Z260 T0100 M05\nN140 M02\n",
 "g76": "G50 X100 Z100\nG97 S500 M03\nG00 X35 Z5\nG76 P021060 Q100 R0.02\nG76 X28.05 Z-40 R0 P975 Q400 F1.5\nG00 X100 Z100\nM30\n",
 "g90": "G50 X100 Z100\nG99 S600 M03\nG00 X55 Z2\nG90 X50 Z-30 F0.2\nX45\nX40 R-2\nG94 X20 Z-2 F0.1\nZ-4\nG00 X100 Z100\nM30\n",
}
for k, v in SEED003.items():
    put("program", "s003_" + k, v)

EDGE = {
 "empty": "", "percent": "%\n%\n", "open_comment": "G00 X10 (never closed\nM30\n",
 "huge": "G00 X99999999999999999999 Z-1e99\nG01 X1.2.3 F--5\nM30\n",
 "macro_while": "#1=0\nWHILE[#1LT1000]DO1\n#1=#1+1\nG01 U0.01 F100\nEND1\nM30\n",
 "macro_forever": "N1 #2=#2+1\nGOTO1\n",
 "macro_div0": "#1=1/0\n#2=SQRT[-1]\n#3=ATAN[0]/[0]\n#4=#[#5]\n#[2000]=1\nM30\n",
 "macro_if": "#1=5\nIF[#1GT3]GOTO10\nG00 X1\nN10 IF[#1EQ5]THEN#2=1\nG01 X#2 Z-#1 F0.1\nM30\n",
 "subs": "O0001\nG00 X10\nM98 P2 L3\nM30\n%\nO0002\nG01 U-1 F100\nM98 P3\nM99\nO0003\nW-1\nM99\n",
 "sub_recursive": "O0001\nM98 P1\nM30\n",
 "m99_main": "G00 X10\nM99\n",
 "nose_comp": "G50 X100 Z100\nT0101\nG42 G00 X20 Z2\nG01 Z-20 F0.1\nG02 X40 Z-30 R10\nG40 G00 X100 Z100\nM30\n",
 "g22": "G22 X100 Z50 I-10 K-100\nG00 X200 Z0\nG23\nM30\n",
 "dwell_tap": "G97 S200 M03\nG04 X1.5\nG00 X0 Z5\nG84 Z-20 F1.0\nG80\nM30\n",
 "g34": "G97 S300 M03\nG00 X30 Z5\nG34 Z-40 F2 K0.1\nG00 X40\nM30\n",
 "stop_m00": "G00 X10\nM00\nM01\nG00 X20\nM30\n",
 "ctrl_bytes": b"G00 X1\x00\x01\x7f\xff\nM30\n",
}
for k, v in EDGE.items():
    put("program", "edge_" + k, v)

# cycles: head byte selects the cycle (head % 9), the rest are parameters.
params = bytes([100, 0, 40, 0, 20, 0, 30, 10, 20, 30, 3, 1, 0x10, 0x27, 0xe8, 0xfc, 5, 0x88, 0x13, 1, 0x58, 0xf2, 2, 0xd0, 0x07, 0x60, 0xf0, 10, 15])
for h in range(9):
    put("cycles", f"cycle{h}", bytes([h]) + params)
    put("cycles", f"cycle{h}_g98", bytes([h | 0x80]) + params)
rng = random.Random(12)
for i in range(6):
    put("cycles", f"random{i}", bytes(rng.randrange(256) for _ in range(48)))

def crc16(data):
    c = 0xFFFF
    for b in data:
        c ^= b << 8
        for _ in range(8):
            c = ((c << 1) ^ 0x1021) & 0xFFFF if c & 0x8000 else (c << 1) & 0xFFFF
    return c

def crc_line(k, text):
    body = f"N{k} {text}"
    return f"{body}*{crc16(body.encode()):04X}\n"

BOARD = {
 "dollar": (0x10, "?$$\n$G\n$#\n$I\n$V\n$PL\n$N\n$\n$999=1\n$RST=$\n?"),
 "stream": (0x08, "?G50 X100 Z100\nG99 S500 M03\nG00 X40 Z2\nG01 Z-20 F0.2\nX60\nM30\n?"),
 "tape": (0x05, "$TAPE\n%\nO0012\nG00 X10\nG01 U-2 F100\nM99\n%\n$PL\n$PR=12\n$PD=12\n"),
 "tape_auto": (0x3f, "%\nG00 X10\nM30\n%\n"),
 "crc": (0x20, crc_line(1, "G00 X10") + crc_line(2, "G01 Z-5 F100") + "N4 M30*0000\n" + crc_line(3, "M30")),
 "estop": (0x88, "G97 S300 M03\nG00 X35 Z5\nG92 X29.2 Z-40 F1.5\nX28.6\nM30\n"),
 "hold": (0x48, "G98 G01 X50 Z-50 F500\nG01 Z-100\nM30\n!~"),
 "door": (0xc8, "G00 X10 Z-10\nG00 X20\nM30\n\x84"),
 "jog": (0x04, "$J=G91 X5 F500\n\x85$J=G90 Z-1000 F100\n$X\n"),
 "home_reset": (0x02, "$H\n\x18$X\n\x91\x92\x93\x94\x95\x96\x97\x99\x9a\x9b\x9c\x9d\x9e\xa0\xa1\x90"),
 "long_line": (0x3f, "G01 " + "X1" * 100 + "\nM30\n"),
 "sleep": (0x01, "$SLP\n?\x18?"),
 "check": (0x10, "$C\nG00 X10\nM30\n$C\n"),
 "binary": (0x07, bytes(range(256)).decode("latin-1")),
}
for k, (h, s) in BOARD.items():
    put("board", k, bytes([h]) + s.encode("latin-1"))
