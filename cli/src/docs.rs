//! `lathe alarms` and `lathe params`: the alarm catalog and the parameter table of
//! `interp-core` as Markdown. docs/ALARMS.md and docs/PARAMETERS.md are exactly
//! this output, and a test keeps them so.

use std::fmt::Write;

use interp_core::alarm::CATALOG;
use interp_core::config::PARAMS;

/// docs/ALARMS.md: the catalog with the manual's sections and the test proving each
/// code, the manual's alarms with our code for each, and those we do not raise.
pub fn alarms_markdown() -> String {
    let mut s = String::from(
        "# Alarms\n\n\
         Every alarm the lathe interpreter raises. A block that raises an alarm changes nothing: \
         the control stops there, `lathe sim` stops there too, and `lathe check` reports it as \
         `PROGRAM:LINE: alarm CODE: message` and goes on with the next block. Under nose radius \
         compensation (G41/G42) or with a `,C`/`,R` waiting, the moves held back from the good \
         blocks before it run first, the last one ending on its normal (2.18.3; a waiting \
         chamfer or corner R is left out), and the faulty block moves nothing; when the held move \
         is itself the fault (3605, its offset would run backwards) the machine stops before it \
         and the alarm names its line. Codes follow the \
         manual where it numbers an alarm, FANUC's numbers where it has an equivalent, and \
         4000-4999 for alarms of this controller alone. This file is generated from \
         `interp_core::alarm::CATALOG` and the tables of `cli/src/docs.rs` by \
         `lathe alarms > docs/ALARMS.md`; a test fails when the two differ.\n\n\
         \"Proven by\" names the case of `host-tests/tests/alarm_table.rs` that runs a program \
         raising the code and checks its line and that the faulty block moved nothing, or the \
         test that proves it where a plain program cannot (a simulated drive, a panel switch).\n\n\
         | Code | Alarm | Raised when | Manual | Proven by |\n\
         | ---: | --- | --- | --- | --- |\n",
    );
    for e in CATALOG {
        let _ = writeln!(
            s,
            "| {:04} | {} | {} | {} | {} |",
            e.code,
            cell(e.title),
            cell(e.when),
            manual_sections(e.code),
            proven_by(e.code)
        );
    }
    manual_tables(&mut s);
    s
}

/// The two tables of the manual's alarms: raised (with codes) and not raised (with why).
fn manual_tables(s: &mut String) {
    let not_raised = MANUAL.iter().filter(|m| matches!(m.outcome, Outcome::NotRaised(_))).count();
    let _ = write!(
        s,
        "\n## The manual's alarms\n\n\
         Every place the manual says a condition raises an alarm (报警, P/S 报警, No.xxxx): {} in \
         all, {} raised, {} not raised (next table). The manual numbers only 3576, 3577, 3605 and \
         3607; the others get FANUC's number or one of ours. Places that name an alarm without \
         one being raised there are left out: 2.10 note 5 (the tool may back out of an \
         overtravel), 2.13 note 5's `G01 X100 Y50 Z20` (no alarm), and 2.17.1 note 5, 2.17.3 \
         note 4, 2.17.4 note 2, 2.22.2 note 5 (a thread or tap decelerates on reset, emergency \
         stop or a drive alarm).\n\n\
         | Section | Alarm in the manual | Code |\n\
         | --- | --- | --- |\n",
        MANUAL.len(),
        MANUAL.len() - not_raised,
        not_raised
    );
    for m in MANUAL {
        if let Outcome::Raised(codes) = m.outcome {
            let codes: Vec<String> = codes.iter().map(|c| format!("{c:04}")).collect();
            let _ = writeln!(s, "| {} | {} | {} |", m.section, cell(m.trigger), codes.join(", "));
        }
    }
    s.push_str(
        "\n## Documented by the manual, not raised\n\n\
         | Section | Alarm in the manual | Why not |\n\
         | --- | --- | --- |\n",
    );
    for m in MANUAL {
        if let Outcome::NotRaised(why) = m.outcome {
            let _ = writeln!(s, "| {} | {} | {} |", m.section, cell(m.trigger), cell(why));
        }
    }
}

/// The manual sections that document `code`, or "-".
fn manual_sections(code: u16) -> String {
    let mut out: Vec<&str> = Vec::new();
    for m in MANUAL {
        if matches!(m.outcome, Outcome::Raised(c) if c.contains(&code)) && !out.contains(&m.section) {
            out.push(m.section);
        }
    }
    if out.is_empty() { "-".into() } else { out.join(", ") }
}

/// The alarm_table cases raising `code`, or the test proving it elsewhere.
fn proven_by(code: u16) -> String {
    let cases: Vec<&str> = PROOFS.iter().filter(|p| p.code == code).map(|p| p.case).collect();
    if !cases.is_empty() {
        return cases.join(", ");
    }
    match PROVEN_ELSEWHERE.iter().find(|e| e.0 == code) {
        Some((_, by)) => cell(by),
        None => "**none**".into(),
    }
}

/// docs/PARAMETERS.md: a header and one row per parameter.
pub fn params_markdown() -> String {
    let mut s = String::from(
        "# Parameters\n\n\
         The numbered parameters of the lathe interpreter, with the manual's numbers. Set them in \
         the `[parameters]` table of a machine file (`lathe sim --machine FILE`) by number, in the \
         unit shown, for example `5147 = 2.0`; a number not listed here is an error. Programs may \
         change some of them while they run (G71 U writes 5147). This file is generated from \
         `interp_core::config::PARAMS` by `lathe params > docs/PARAMETERS.md`; a test fails when \
         the two differ.\n\n\
         | No. | Unit | Default | Meaning |\n\
         | ---: | --- | ---: | --- |\n",
    );
    for p in PARAMS {
        let _ = writeln!(s, "| {} | {} | {} | {} |", p.number, p.unit.name(), p.default, cell(p.meaning()));
    }
    s
}

/// How a proof program of [`PROOFS`] is run.
#[derive(Clone, Copy, Debug)]
pub enum Setup {
    /// The program alone on the built-in machine.
    Plain,
    /// The program as main program with these subprograms in memory.
    Library(&'static [&'static str]),
    /// The program on the machine described by this TOML text (`lathe sim --machine`).
    Machine(&'static str),
    /// The text typed in MDI (the alarm has line 0).
    Mdi,
}

/// A program that raises one alarm: the test case `host-tests/tests/alarm_table.rs`
/// runs for it and the "proven by" column of docs/ALARMS.md.
#[derive(Clone, Copy, Debug)]
pub struct Proof {
    /// Name of the case, as the test reports it and docs/ALARMS.md shows it.
    pub case: &'static str,
    /// The alarm code expected.
    pub code: u16,
    /// How to run the program.
    pub setup: Setup,
    /// The program text.
    pub program: &'static str,
    /// O number of the program the faulty block is in (0: the main program).
    pub in_program: u32,
    /// 1-based line of the faulty block.
    pub line: u32,
}

/// Shorthand for a [`Proof`] of the main program on the built-in machine.
const fn plain(case: &'static str, code: u16, program: &'static str, line: u32) -> Proof {
    Proof { case, code, setup: Setup::Plain, program, in_program: 0, line }
}

/// The machine of examples/machines/nose_radius.toml: nose R0.8 (tip 3) in offset row 1.
const NOSE: Setup = Setup::Machine(include_str!("../../examples/machines/nose_radius.toml"));

/// The machine of examples/machines/polar_c_axis.toml: a C axis for polar interpolation.
const C_AXIS: Setup = Setup::Machine(include_str!("../../examples/machines/polar_c_axis.toml"));

/// The machine of examples/machines/mill.toml: a 3-axis machining centre.
const MILL: Setup = Setup::Machine(include_str!("../../examples/machines/mill.toml"));

/// Shorthand for a [`Proof`] of the main program run with `setup`.
const fn on(setup: Setup, case: &'static str, code: u16, program: &'static str, line: u32) -> Proof {
    Proof { case, code, setup, program, in_program: 0, line }
}

/// One program per alarm code (several where the manual names several causes).
pub const PROOFS: &[Proof] = &[
    plain("too_many_digits", 3, "G00 X1\nX1234567890\nM30\n", 2),
    plain("number_without_address", 4, "G00 X1\n5 X1\nM30\n", 2),
    plain("address_without_number", 5, "G00 X1\nG00 X\nM30\n", 2),
    plain("minus_on_m", 6, "G00 X1\nM-3\nM30\n", 2),
    plain("point_on_g04_p", 7, "G00 X1\nG04 P2.5\nM30\n", 2),
    plain("unused_address_d", 9, "G00 X1\nD5\nM30\n", 2),
    plain("axis_not_on_machine", 9, "G00 X1\nG00 Y5\nM30\n", 2),
    plain("g_code_not_in_system", 10, "G00 X1\nG07 X1\nM30\n", 2),
    plain("feed_never_set", 11, "G00 X1\nG01 X10\nM30\n", 2),
    plain("g34_lead_turns_negative", 14, "M3 S500\nG34 W-78 F4 K-0.2\nM30\n", 2),
    plain("arc_r_too_short", 20, "G00 X60 Z0\nG02 W-20 R5 F100\nM30\n", 2),
    plain(
        "g71_shape_arc_off_circle",
        20,
        "G00 X100 Z5\nG71 U1 R0.5 F100\nG71 P10 Q20\nN10 G00 X40 Z0\nG01 Z-10\nG02 X60 Z-20 I10 K-3\nN20 G01 X80\nM30\n",
        3,
    ),
    plain("arc_axis_outside_plane", 21, "G17\nG00 X10 Z0\nG02 X20 Z50 R100 F100\nM30\n", 3),
    plain("arc_without_center", 22, "G00 X20 Z0\nG02 X30 Z-5 F100\nM30\n", 2),
    plain("arc_radius_zero", 23, "G00 X1\nG02 X10 R0 F100\nM30\n", 2),
    plain("tool_not_on_turret", 30, "G00 X1\nT0140\nM30\n", 2),
    on(NOSE, "comp_starts_on_arc", 34, "T0101\nG00 X20 Z5\nG42 G02 X30 Z0 R5 F0.1\nM30\n", 3),
    on(NOSE, "comp_ends_on_arc", 34, "T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nG40 G02 X30 Z-5 R5\nM30\n", 4),
    on(NOSE, "plane_change_in_comp", 37, "T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nG17 X30\nM30\n", 4),
    on(C_AXIS, "polar_start_in_comp", 37, "G00 X60 C0\nG42 G01 X50 F100\nG12.1\nM30\n", 3),
    on(MILL, "mill_lathe_code", 10, "G00 X-10 Y-10\nG71 U1 R0.5\nM30\n", 2),
    on(MILL, "mill_h_outside_table", 30, "G00 X-10 Y-10\nG43 Z50 H33\nM30\n", 2),
    on(MILL, "mill_g10_value_too_large", 32, "G00 X-10\nG10 L10 P1 R1000.\nM30\n", 2),
    on(MILL, "mill_g28_in_hole_cycle", 44, "G00 X0 Y0 Z50\nG81 X10 Z-5 R2 F100\nG28 Z0\nM30\n", 3),
    on(MILL, "mill_g83_without_q", 45, "G00 X0 Y0 Z50\nG83 X10 Z-5 R2 F100\nM30\n", 2),
    plain("g30_p7", 46, "G00 X1\nG30 P7 U0\nM30\n", 2),
    plain("chamfer_in_thread", 50, "M3 S500\nG32 W-30 F2 ,C1\nM30\n", 2),
    plain("chamfer_then_rapid", 51, "G01 W-20 F100 ,C1\nG00 U10\nM30\n", 2),
    plain("corner_r_too_large", 55, "G01 W-20 F100 ,R5\nU2\nM30\n", 2),
    plain("g71_without_q", 61, "G00 X1\nG71 P10 U1\nM30\n", 2),
    plain("g71_negative_depth", 62, "G00 X1\nG71 U-1\nM30\n", 2),
    plain("g76_without_height", 62, "M3 S500\nG0 X40 Z5\nG76 P011060\nG76 X30 Z-20 Q0.5 F2\nM30\n", 4),
    plain("g76_allowance_above_height", 62, "M3 S500\nG0 X40 Z5\nG76 P011060 R2\nG76 X30 Z-20 P1.0 Q0.5 F2\nM30\n", 4),
    plain("g70_sequence_missing", 63, "G00 X1\nG70 P10 Q20\nM30\n", 2),
    plain("g71_shape_not_monotone", 64, "G00 X100 Z5\nG71 P10 Q30 F100\nN10 G00 X40\nG01 Z-10\nN30 Z-5\nM30\n", 2),
    plain("g71_ns_without_g00_g01", 65, "G00 X100 Z5\nG71 P10 Q30 F100\nN10 X40\nN30 G01 Z-5\nM30\n", 2),
    plain("g71_shape_with_g28", 66, "G00 X100 Z5\nG71 P10 Q30 F100\nN10 G00 X40\nG28 U0\nN30 G01 Z-5\nM30\n", 2),
    plain("m98_program_missing", 76, "G00 X1\nM98 P12\nM30\n", 2),
    plain("m98_without_p", 76, "G00 X1\nM98\nM30\n", 2),
    Proof {
        case: "m98_nesting_13_levels",
        code: 77,
        setup: Setup::Library(&["O0001\nM98 P2\nM99\n", "O0002\nM98 P1\nM99\n"]),
        program: "G00 X1\nM98 P1\nM30\n",
        in_program: 2,
        line: 2,
    },
    plain("g65_program_missing", 76, "G00 X1\nG65 P12 A1.\nM30\n", 2),
    plain("g66_without_p", 76, "G00 X1\nG66 A1.\nM30\n", 2),
    Proof {
        case: "g65_nesting_5_macro_levels",
        code: 77,
        setup: Setup::Library(&["O0001\nG65 P1\nM99\n"]),
        program: "G00 X1\nG65 P1\nM30\n",
        in_program: 1,
        line: 2,
    },
    plain("goto_missing_sequence", 78, "G00 X1\nGOTO 5\nM30\n", 2),
    Proof {
        case: "m99_p_missing_sequence",
        code: 78,
        setup: Setup::Library(&["O0001\nG00 X2\nM99 P77\n"]),
        program: "G00 X1\nM98 P1\nM30\n",
        in_program: 1,
        line: 3,
    },
    plain("macro_overflow", 111, "#1=EXP[80]\nG00 X1\n#2=#1*#1*#1*#1*#1*#1*#1*#1*#1*#1\nM30\n", 3),
    plain("divide_by_zero", 112, "G00 X1\n#1=1/0\nM30\n", 2),
    plain("tan_90", 112, "G00 X1\nG00 X[TAN[90]]\nM30\n", 2),
    plain("bracket_not_closed", 114, "G00 X1\n#1=[1\nM30\n", 2),
    plain("variable_1000", 115, "G00 X1\n#1=#1000\nM30\n", 2),
    plain("write_to_null", 116, "G00 X1\n#0=1\nM30\n", 2),
    plain("six_brackets", 118, "G00 X1\n#1=[[[[[[1]]]]]]\nM30\n", 2),
    plain("sqrt_negative", 119, "G00 X1\n#1=SQRT[-1]\nM30\n", 2),
    plain("asin_of_2", 119, "G00 X1\n#1=ASIN[2]\nM30\n", 2),
    Proof { case: "goto_in_mdi", code: 123, setup: Setup::Mdi, program: "GOTO 1", in_program: 0, line: 0 },
    plain("end_without_do", 124, "G00 X1\nEND1\nM30\n", 2),
    plain("do_without_end", 124, "G00 X1\nWHILE [1 EQ 1] DO1\nM30\n", 2),
    plain("do_label_4", 126, "G00 X1\nDO4\nM30\n", 2),
    plain("macro_and_nc_words", 127, "G00 X1\n#1=1 G00\nM30\n", 2),
    Proof {
        case: "g66_four_fold",
        code: 122,
        setup: Setup::Library(&["O0001\nM99\n"]),
        program: "G00 X1\nG66 P1\nG66 P1\nG66 P1\nG66 P1\nM30\n",
        in_program: 0,
        line: 5,
    },
    plain("goto_0", 128, "G00 X1\nGOTO 0\nM30\n", 2),
    plain("g65_g_as_argument", 129, "G00 X1\nG65 P1 G01\nM30\n", 2),
    plain("m29_without_s", 200, "G00 X1\nM29\nM30\n", 2),
    plain("s_after_m29", 203, "M29 S100\nS200\nM30\n", 2),
    plain("m29_twice", 203, "M29 S100\nM29 S100\nM30\n", 2),
    plain("move_after_m29", 204, "M29 S100\nG00 X10\nM30\n", 2),
    on(MILL, "mill_g51_p_out_of_range", 142, "G00 X0 Y0\nG51 X0 Y0 P1000000\nM30\n", 2),
    plain("plane_after_chamfer", 212, "G01 W-20 F100 ,C1\nG19 U10\nM30\n", 2),
    on(MILL, "mill_plane_change_in_g68", 212, "G68 X0 Y0 R30.\nG00 X10 Y0\nG18\nM30\n", 3),
    plain(
        "g71_type1_not_monotone_in_x",
        329,
        "G00 X100 Z5\nG71 P10 Q30 F100\nN10 G00 X40\nG01 Z-10\nN30 X30 Z-15\nM30\n",
        2,
    ),
    plain("x_past_soft_limit", 500, "G00 X1\nG00 X400\nM30\n", 2),
    plain("z_past_soft_limit", 501, "G00 X1\nG00 Z-800\nM30\n", 2),
    plain("move_into_g22_area_plus", 502, "G22 X40 Z-10 I20 K-30\nG00 X10 Z-5\nG01 X50 Z-35 F100\nM30\n", 3),
    plain("move_into_g22_area_minus", 503, "G22 X40 Z-10 I20 K-30\nG00 X30 Z0\nG01 Z-40 F100\nM30\n", 3),
    plain("g22_on_after_g23_inside", 502, "G00 X30 Z-20\nG22 X40 Z-10 I20 K-30\nG00 X31\nM30\n", 3),
    plain("g28_via_g22_area", 503, "G00 X100 Z50\nG22 X40 Z-10 I20 K-30\nG28 X30 Z-20\nM30\n", 3),
    Proof {
        case: "g22_outside_type_immediately",
        code: 502,
        setup: Setup::Machine("[parameters]\n1002 = 1\n"),
        program: "G00 X100 Z50\nG22 X40 Z-10 I20 K-30\nG00 X101\nM30\n",
        in_program: 0,
        line: 2,
    },
    on(NOSE, "g41_straight_after_g42", 3576, "T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nG41 X20\nM30\n", 4),
    on(NOSE, "t_in_comp", 3577, "T0101\nG00 X0 Z5\nG42 G01 Z0 F0.1\nT0202\nM30\n", 4),
    on(
        NOSE,
        "inside_arc_smaller_than_nose",
        3605,
        "T0101\nG00 X20 Z5\nG41 G01 Z0 F0.1\nZ-10\nG03 X21 Z-10.5 R0.5\nG01 Z-20\nG40 X40\nM30\n",
        5,
    ),
    on(
        NOSE,
        "groove_narrower_than_nose",
        3605,
        "T0101\nG00 X40 Z5\nG42 G01 Z0 F0.1\nZ-10\nX30\nZ-11\nX40\nZ-20\nG40 X60\nM30\n",
        6,
    ),
    on(NOSE, "corner_under_0_1_degree", 3607, "T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nZ-10\nZ0\nM30\n", 5),
    plain("g20_with_a_move", 4001, "G20 X1\nM30\n", 1),
    plain("g20_after_motion", 4002, "G00 X10\nG20\nM30\n", 2),
    Proof { case: "cycle_in_mdi", code: 4007, setup: Setup::Mdi, program: "G90 X10 Z-5 F100", in_program: 0, line: 0 },
    plain("g00_with_g01", 4003, "G00 X1\nG00 G01 X1\nM30\n", 2),
    plain("x_twice", 4004, "G00 X1\nG00 X1 X2\nM30\n", 2),
    plain("i_on_g00", 4005, "G00 X1\nG00 X1 I2\nM30\n", 2),
    plain("g52_without_axes", 4006, "G00 X1\nG52\nM30\n", 2),
    Proof {
        case: "g50_disabled",
        code: 4012,
        setup: Setup::Machine("[parameters]\n5152 = 1\n"),
        program: "G00 X1\nG50 X1\nM30\n",
        in_program: 0,
        line: 2,
    },
    plain("m77_unknown", 4008, "G00 X1\nM77\nM30\n", 2),
    plain("m8_with_m9", 4009, "G00 X1\nM8 M9\nM30\n", 2),
    plain("four_m_codes", 4010, "G00 X1\nM3 M8 M41 M1\nM30\n", 2),
    plain("s_too_large", 4011, "G00 X1\nS100000\nM30\n", 2),
    plain("g99_feed_spindle_stopped", 4013, "G00 X1\nG99 G01 X1 F1\nM30\n", 2),
    plain("comment_not_closed", 4014, "G00 X1\nG00 X1 (open\nM30\n", 2),
    plain("g53_incremental", 4015, "G00 X1\nG53 W10\nM30\n", 2),
    plain("g28_with_g00", 4016, "G00 X1\nG00 G28 U0\nM30\n", 2),
    plain("g22_with_g00", 4016, "G00 X1\nG22 G00 X40 Z-10 I20 K-30\nM30\n", 2),
    plain("block_skip_mid_block", 4018, "G00 X1\nG00 X1 / Z1\nM30\n", 2),
    plain("dollar_sign", 4019, "G00 X1\nG00 X1 $\nM30\n", 2),
    plain("x_with_u", 4020, "G00 X1\nG00 X1 U1\nM30\n", 2),
    plain("g32_x_with_u", 4020, "M3 S500\nG32 X10 U2 W-10 F1\nM30\n", 2),
    plain("g90_taper_too_large", 4030, "G00 X100 Z10\nG90 U-40 W-30 R21 F100\nM30\n", 2),
    plain("g90_in_g17", 4031, "G17\nG90 X10 Z-5 F100\nM30\n", 2),
    on(C_AXIS, "g90_moves_c", 4032, "G00 X20 Z5\nG90 X10 C5 Z-5 F100\nM30\n", 2),
    plain("g32_q_361", 4033, "M3 S500\nG32 W-30 F2 Q361\nM30\n", 2),
    plain("g92_pullout_too_long", 4034, "M3 S500\nG0 X40 Z5\nG92 X30 W-3 F5\nM30\n", 3),
    plain("g76_pullout_too_long", 4034, "M3 S500\nG00 X40 Z5\nG76 P011060\nG76 X30 Z-20 P1.0 Q0.5 F50\nM30\n", 4),
    plain("g74_million_moves", 4037, "G0 X40 Z5 M3 S500\nG74 R0.5\nG74 X20 Z-20 P3 Q5 F50\nM30\n", 3),
    Proof {
        case: "m98_calls_itself",
        code: 4040,
        setup: Setup::Library(&["O0001\nG00 X2\nM98 P1\nM99\n"]),
        program: "G00 X1\nM98 P1\nM30\n",
        in_program: 1,
        line: 3,
    },
    Proof { case: "m98_in_mdi", code: 4041, setup: Setup::Mdi, program: "M98 P1", in_program: 0, line: 0 },
    on(Setup::Machine("jump_input = 40\n"), "m92_input_missing", 4043, "G00 X1\nM92 P1\nN1 M30\n", 2),
    on(
        NOSE,
        "five_m_blocks_behind_held_move",
        4044,
        "T0101\nG00 X20 Z5\nG42 G01 Z0 F0.1\nM08\nM09\nM08\nM09\nM08\nZ-10\nM30\n",
        8,
    ),
    on(C_AXIS, "g00_in_polar", 4045, "G00 X60 C0\nG12.1\nG00 X40\nM30\n", 3),
    on(C_AXIS, "g28_in_polar", 4045, "G00 X60 C0\nG12.1\nG28 U0\nM30\n", 3),
    on(C_AXIS, "polar_arc_with_i", 4046, "G00 X60 C0\nG12.1\nG02 X40 C10 I5 F100\nM30\n", 3),
    plain("m99_with_x", 4042, "G00 X1\nM99 X1\nM30\n", 2),
    plain("g51_2_without_tool_spindle", 4047, "G00 X1\nG51.2 P1 Q2\nM30\n", 2),
    on(MILL, "mill_g29_without_g28", 4048, "G00 X10 Y10\nG29 X0 Y0\nM30\n", 2),
    on(MILL, "mill_g51_in_cutter_comp", 4049, "G00 X-10 Y-10 Z10\nG41 D1 G01 X0 Y0 F300\nG51 X0 Y0 P2000\nM30\n", 3),
    on(MILL, "mill_g51_1_after_g51", 4051, "G51 X0 Y0 P2000\nG51.1 X0\nM30\n", 2),
    on(MILL, "mill_hole_cycle_without_r", 4006, "G00 X0 Y0 Z50\nG81 X10 Z-5 F100\nM30\n", 2),
    on(MILL, "mill_g51_1_without_axis", 4006, "G00 X-10 Y-10\nG51.1\nG01 X-20 F100\nM30\n", 2),
    on(MILL, "mill_g52_under_g91", 4015, "G00 X-10 Y-10\nG91 G52 X10\nG90 G00 X0 Y0\nM30\n", 2),
    on(MILL, "mill_t_above_tool_count", 30, "G00 X-10 Y-10\nT30 M06\nM30\n", 2),
    on(MILL, "mill_u_address", 9, "G00 X1\nG00 U10\nM30\n", 2),
    on(MILL, "mill_m06_in_cutter_comp", 3577, "G00 X-10 Y-10 Z10\nG41 D1 G01 X0 Y0 F300\nT2 M06\nM30\n", 3),
    on(
        MILL,
        "mill_groove_narrower_than_cutter",
        3605,
        "G00 X-10 Y10 Z-5\nG41 D1 G01 X0 Y0 F300\nX20\nY-4\nX24\nY0\nX50\nG40 X60 Y10\nM30\n",
        5,
    ),
    on(C_AXIS, "c_move_in_polygon_turning", 220, "G51.2 P1 Q2 S300\nG00 X50\nG00 C10\nG50.2\nM30\n", 3),
    on(C_AXIS, "polar_in_polygon_turning", 221, "G51.2 P1 Q2 S300\nG00 X50\nG12.1\nG13.1\nG50.2\nM30\n", 3),
    plain("variables_full", 4050, "#1=0\nWHILE [#1 LT 200] DO1\n#[200+#1]=1\n#1=#1+1\nEND1\nM30\n", 3),
    plain("no_m30", 5010, "G00 X10\n", 2),
];

/// Catalog codes without a [`PROOFS`] case: the test that proves each instead and why
/// it cannot be a plain program (a simulated drive, a switch of the operator panel …).
pub const PROVEN_ELSEWHERE: &[(u16, &str)] = &[
    (224, "alarms.rs alarms_needing_a_machine_setting (axis not referenced: a panel switch)"),
    (4017, "alarms.rs alarms_needing_a_machine_setting (400 far moves on unlimited axes)"),
    (4035, "alarms.rs cycle_alarms_needing_a_machine_or_a_long_program (49-segment shape)"),
    (4036, "alarms.rs cycle_alarms_needing_a_machine_or_a_long_program (11 pockets)"),
    (
        4052,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (MCALL in a modally called SINUMERIK subprogram)",
    ),
    (4501, "alarms.rs motion_alarms_are_raised_with_their_line (simulated drive)"),
    (4502, "alarms.rs motion_alarms_are_raised_with_their_line (simulated drive)"),
    (4503, "alarms.rs motion_alarms_are_raised_with_their_line (simulated spindle)"),
    (4504, "alarms.rs motion_alarms_are_raised_with_their_line (simulated spindle)"),
    (4505, "alarms.rs motion_alarms_are_raised_with_their_line (simulated drive)"),
    (4506, "alarms.rs motion_alarms_are_raised_with_their_line (simulated spindle)"),
    (4507, "alarms.rs motion_alarms_are_raised_with_their_line (actions fed to the motion core)"),
    (4508, "alarms.rs motion_alarms_are_raised_with_their_line (machine configuration)"),
    (4509, "alarms.rs motion_alarms_are_raised_with_their_line (emergency stop input)"),
    (4510, "alarms.rs motion_alarms_are_raised_with_their_line (simulated drive)"),
    (
        4511,
        "controller mill.rs no_done_within_313_seconds_is_alarm_4511_and_nothing_moves (a tool changer that never \
         answers; the time the controller is given) and cli board.rs (lathe board --atc-never)",
    ),
    (4601, "controller starve.rs (a stream cut mid-job; the time the controller is given) and sim faults.rs"),
    (
        12080,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        12150,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        12160,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        12170,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        12330,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        12340,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        12460,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        12470,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        12550,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        14011,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        14012,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        14080,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        14500,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        14510,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        16420,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        17020,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        17180,
        "host-tests siemens_language.rs alarms_of_the_language_with_their_numbers_and_lines (and the 12330/12340, 16420 tests there: a SINUMERIK program)",
    ),
    (
        61000,
        "interp-siemens cycles::tests::undercut.rs undercut_alarms_move_nothing, groove.rs cycle93_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61001,
        "interp-siemens cycles::tests::threads.rs thread_alarms_move_nothing, undercut.rs undercut_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61002,
        "interp-siemens cycles::tests::threads.rs thread_alarms_move_nothing, stock.rs cycle95_alarms_move_nothing, groove.rs cycle93_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (61003, "interp-siemens cycles::mill tests (the milling cycles' shared tool, feed, width and level checks)"),
    (
        61005,
        "interp-siemens cycles::tests::drill.rs drilling_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (61009, "interp-siemens cycles::mill tests (the milling cycles' shared tool, feed, width and level checks)"),
    (
        61019,
        "interp-siemens cycles::tests::drill.rs drilling_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61101,
        "interp-siemens cycles::tests::drill.rs drilling_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61102,
        "interp-siemens cycles::tests::drill.rs drilling_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (61103, "host-tests siemens_holes.rs alarms_of_the_patterns_move_nothing"),
    (61104, "host-tests siemens_slots.rs alarms_of_the_slots_move_nothing"),
    (
        61106,
        "host-tests siemens_holes.rs alarms_of_the_patterns_move_nothing, siemens_slots.rs alarms_of_the_slots_move_nothing",
    ),
    (61105, "interp-siemens cycles::mill tests (the milling cycles' shared tool, feed, width and level checks)"),
    (
        61107,
        "interp-siemens cycles::tests::drill.rs drilling_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (61108, "host-tests siemens_pockets.rs alarms_of_pocket3_and_pocket4_move_nothing"),
    (61109, "host-tests siemens_pockets.rs alarms_of_pocket3_and_pocket4_move_nothing"),
    (61110, "host-tests siemens_pockets.rs alarms_of_pocket3_and_pocket4_move_nothing"),
    (61111, "interp-siemens cycles::mill tests (the milling cycles' shared tool, feed, width and level checks)"),
    (61112, "interp-siemens cycles::mill tests (the milling cycles' shared tool, feed, width and level checks)"),
    (61113, "host-tests siemens_pockets.rs alarms_of_pocket3_and_pocket4_move_nothing"),
    (61116, "host-tests siemens_contour alarms_move_nothing (CYCLE72 _LP1/_LP2 = 0)"),
    (61117, "interp-siemens cycles::mill tests (the milling cycles' shared tool, feed, width and level checks)"),
    (
        61125,
        "interp-siemens cycles::tests::drill.rs drilling_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (61128, "host-tests siemens_slots.rs alarms_of_the_slots_move_nothing"),
    (61176, "host-tests siemens_engrave.rs alarms_of_cycle60_move_nothing"),
    (61178, "host-tests siemens_engrave.rs alarms_of_cycle60_move_nothing"),
    (61179, "host-tests siemens_engrave.rs alarms_of_cycle60_move_nothing"),
    (61180, "host-tests siemens_thread_mill.rs cycle800_swivels_raise_61180_and_deselect_is_accepted"),
    (61191, "host-tests siemens_hsc.rs alarms_on_the_cycles_line_and_nothing_changes"),
    (61192, "host-tests siemens_hsc.rs alarms_on_the_cycles_line_and_nothing_changes"),
    (61194, "host-tests siemens_hsc.rs alarms_on_the_cycles_line_and_nothing_changes"),
    (
        61601,
        "interp-siemens cycles::tests::undercut.rs undercut_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61602,
        "interp-siemens cycles::tests::groove.rs cycle93_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61603,
        "interp-siemens cycles::tests::groove.rs cycle93_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61604,
        "interp-siemens cycles::tests::stock.rs cycle95_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61605,
        "interp-siemens cycles::tests::stock.rs cycle95_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61606,
        "interp-siemens cycles::tests::stock.rs cycle95_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61607,
        "interp-siemens cycles::tests::stock.rs cycle95_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61608,
        "interp-siemens cycles::tests::undercut.rs undercut_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61609,
        "interp-siemens cycles::tests::undercut.rs undercut_alarms_move_nothing (the cycle called directly until SINUMERIK programs run); host-tests siemens_slots.rs alarms_of_the_slots_move_nothing",
    ),
    (
        61612,
        "interp-siemens cycles::tests::threads.rs cycle97_recut_start_angle (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61613,
        "interp-siemens cycles::tests::undercut.rs undercut_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61701,
        "interp-siemens cycles::tests::stock.rs cycle950_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61702,
        "interp-siemens cycles::tests::stock.rs cycle950_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61720,
        "interp-siemens cycles::tests::stock.rs cycle950_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61721,
        "interp-siemens cycles::tests::stock.rs cycle950_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61803,
        "interp-siemens cycles::tests::drill.rs drilling_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (
        61807,
        "interp-siemens cycles::tests::drill.rs drilling_alarms_move_nothing (the cycle called directly until SINUMERIK programs run)",
    ),
    (61900, "host-tests siemens_island.rs transfer_alarms_move_nothing"),
    (61901, "host-tests siemens_island.rs geometry_alarms_move_nothing"),
    (61903, "host-tests siemens_island.rs geometry_alarms_move_nothing"),
    (61904, "mill-paths island::tests every_alarm_has_its_case"),
    (
        61905,
        "host-tests siemens_slots.rs alarms_of_the_slots_move_nothing; siemens_island.rs geometry_alarms_move_nothing (CYCLE73)",
    ),
    (61906, "host-tests siemens_island.rs transfer_alarms_move_nothing"),
    (61908, "host-tests siemens_island.rs geometry_alarms_move_nothing"),
    (61909, "host-tests siemens_island.rs cycle73_alarms_move_nothing"),
    (61910, "host-tests siemens_island.rs geometry_alarms_move_nothing"),
    (61911, "mill-paths island::tests every_alarm_has_its_case"),
    (61912, "host-tests siemens_island.rs geometry_alarms_move_nothing"),
    (61913, "host-tests siemens_island.rs geometry_alarms_move_nothing"),
    (61914, "mill-paths island::tests every_alarm_has_its_case"),
    (61915, "mill-paths island::tests every_alarm_has_its_case"),
    (61916, "mill-paths island::tests every_alarm_has_its_case"),
    (61918, "host-tests siemens_island.rs cycle73_alarms_move_nothing"),
    (61980, "host-tests siemens_island.rs transfer_alarms_move_nothing"),
    (61982, "host-tests siemens_island.rs cycle73_alarms_move_nothing"),
    (61983, "host-tests siemens_island.rs transfer_alarms_move_nothing"),
    (61984, "host-tests siemens_island.rs cycle73_alarms_move_nothing"),
    (61985, "host-tests siemens_island.rs cycle73_alarms_move_nothing"),
    (61988, "host-tests siemens_island.rs cycle73_alarms_move_nothing"),
    (61989, "host-tests siemens_island.rs cycle73_alarms_move_nothing"),
    (
        61011,
        "interp-siemens cycles::tests::face scaling_alarms (no SINUMERIK program sets a scaling yet: the state is scaled directly)",
    ),
    (
        61012,
        "interp-siemens cycles::tests::face scaling_alarms (no SINUMERIK program sets a scaling yet: the state is scaled directly)",
    ),
    (61118, "host-tests siemens_face.rs alarms_move_nothing"),
    (61124, "host-tests siemens_face.rs alarms_move_nothing"),
    (61213, "host-tests siemens_face.rs alarms_move_nothing"),
    (61215, "host-tests siemens_face.rs alarms_move_nothing"),
    (61610, "host-tests siemens_face.rs alarms_move_nothing"),
];

/// What this controller does where the manual says "报警" (alarm).
#[derive(Clone, Copy, Debug)]
pub enum Outcome {
    /// Raised with these codes.
    Raised(&'static [u16]),
    /// Not raised, and why.
    NotRaised(&'static str),
}

/// One alarm the manual documents: its section, what triggers it, our answer.
#[derive(Clone, Copy, Debug)]
pub struct ManualAlarm {
    /// Manual section and note, e.g. "2.3 note 2".
    pub section: &'static str,
    /// What triggers it, in the manual's words (translated).
    pub trigger: &'static str,
    /// The code we raise, or why we do not.
    pub outcome: Outcome,
}

/// Shorthand for a [`ManualAlarm`] we raise.
const fn raised(section: &'static str, trigger: &'static str, codes: &'static [u16]) -> ManualAlarm {
    ManualAlarm { section, trigger, outcome: Outcome::Raised(codes) }
}

/// Every place the manual says a condition raises an alarm (报警, P/S 报警, No.xxxx),
/// in manual order. Places that only mention an alarm in passing (the thread stops
/// on a drive alarm, 2.17.1 note 5) are not alarms of their own and are left out.
pub const MANUAL: &[ManualAlarm] = &[
    raised("2.3 note 2", "G02/G03 with neither R nor I/J/K and parameter 3403 set to alarm", &[22]),
    raised("2.3 note 7", "G02/G03 with an axis outside the selected plane", &[21]),
    raised("2.7", "a G code polar interpolation does not allow, in G12.1", &[4045]),
    raised("2.7 note 8", "G12.1/G13.1 while nose compensation (G41/G42) is active", &[37]),
    ManualAlarm {
        section: "2.7 note 9",
        trigger: "in G12.1 the C-axis share of the feed exceeds the C axis's maximum cutting feed near the centre",
        outcome: Outcome::NotRaised(
            "the planner slows every move so that no axis, C included, exceeds its maximum feed; \
             the tool slows down near the centre instead of stopping",
        ),
    },
    raised("2.8 note 6", "polygon turning (G51.2) without both spindles in position control", &[4047]),
    raised("2.9 note 2", "G20/G21 not alone in its block", &[4001]),
    raised("2.9 note 2", "G20/G21 not at the start of the program", &[4002]),
    ManualAlarm {
        section: "2.10 note 4",
        trigger: "G22 on and the reference point inside the forbidden area: alarm right after the reference return",
        outcome: Outcome::NotRaised(
            "the area is checked against moves only: a G28/G30 return that enters it raises 0502/0503 \
             like any move, but a reference point lying inside it is not reported by itself",
        ),
    },
    raised("2.10", "a move entering the forbidden area of stored stroke check 2", &[502, 503]),
    raised("2.10 note 6", "G22/G23 sharing its block with another G code", &[4016]),
    raised("2.10 note 7", "G22 switched on with the tool in an inside-type area: alarm on the next move", &[502, 503]),
    raised("2.10 note 7", "G22 switched on with the tool in an outside-type area: alarm at once", &[502, 503]),
    raised("2.13 note 4", "G70-G76, G90, G92, G94 outside the ZX plane", &[4031]),
    raised("2.13 note 5", "an arc block with an axis outside the selected plane (G17 G02 X Z)", &[21]),
    raised("2.15 note 1", "a G90/G92/G94 block moving an axis other than X/Z", &[4032]),
    raised(
        "2.16.1 note 6",
        "an arc of the G71 finishing shape off its circle by more than parameter 3410, whatever the allowance",
        &[20],
    ),
    raised("2.16.7 note 2", "the ns block of G71/G72/G73 without G00 or G01", &[65]),
    raised("2.17.1", "G32 start angle Q above 360 or below 0", &[4033]),
    ManualAlarm {
        section: "2.17.1 note 6",
        trigger: "G32 thread pull-out longer than the thread along the long axis",
        outcome: Outcome::NotRaised(
            "G32 cuts no pull-out here (J/K are not accepted and raise 4005); the pull-out of G92 and \
             G76 raises 4034",
        ),
    },
    raised("2.17.1 note 7", "in G32 a base axis and its parallel axis in one block (X with U is our case)", &[4020]),
    raised("2.17.2", "G34 K out of range, or a lead that would become zero, negative or too large", &[14]),
    raised("2.17.3 note 5", "G92 pull-out longer than the thread along the long axis", &[4034]),
    raised("2.17.4", "G76 without the thread height P(k) or the first depth Q(d)", &[62]),
    raised("2.17.4 note 7", "G76 minimum cut or finishing allowance larger than the thread height", &[62]),
    raised("2.17.4 note 8", "G76 pull-out longer than the thread along the long axis", &[4034]),
    raised("2.18.4", "No.3605: nose compensation would gouge the part (interference)", &[3605]),
    raised("2.18.4 1", "No.3607: corner between two moves under 0.1 degree in compensation", &[3607]),
    raised("2.18.4 2", "No.3576: G41 switched straight to G42 or back in compensation", &[3576]),
    raised("2.18.4 3", "No.3577: a T code in compensation", &[3577]),
    raised("2.22.1", "S between M29 and G84/G88, or M29 given twice", &[203]),
    raised("2.22.1", "an axis move between M29 and G84/G88", &[204]),
    raised("2.23 note 2", "the block after a ,C/,R block is not a G01/G02/G03 move", &[51]),
    raised("2.23 note 3", "a chamfer or corner R longer than the moves it joins", &[55]),
    raised("2.23 note 4", "plane selection G17/G18/G19 in the block after a ,C/,R block", &[212]),
    raised("2.23 note 8", ",C or ,R in a thread block", &[50]),
    raised("2.24.2", "ASIN/ACOS of a value outside -1 to 1", &[119]),
    raised("2.24.2", "P/S: division by zero or TAN[90]", &[112]),
    raised("2.24.2", "P/S: a DO/END label other than 1, 2, 3 (also note 3)", &[126]),
    raised("2.24.2 note 1", "P/S: GOTO to a sequence number outside 1-99999", &[128]),
    raised("2.24.2 note 4", "P/S: DO ranges that cross", &[124]),
    raised("3.1.6 note 1", "M98 names a subprogram that is not found", &[76]),
    raised("3.1.6 note 2", "M98 P in MDI", &[4041]),
    raised("3.1.6 note 3", "M98 calls the program it is in", &[4040]),
    raised("3.1.6 note 4", "M98 without P", &[76]),
    raised("3.1.7 note 2", "M99 P names a sequence number that does not exist", &[78]),
];

/// Text safe inside a Markdown table cell.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_have_a_row_per_entry() {
        let a = alarms_markdown();
        // Header and separator rows of three tables, then one row per entry.
        assert_eq!(a.lines().filter(|l| l.starts_with("| ")).count(), CATALOG.len() + MANUAL.len() + 6);
        assert!(a.contains("| 0010 | improper G code |"));
        assert!(a.contains("| 3577 | "));
        assert!(!a.contains("**none**"), "a catalog code is proven by nothing");
        let p = params_markdown();
        assert_eq!(p.lines().filter(|l| l.starts_with("| ")).count(), PARAMS.len() + 2);
        assert!(p.contains("| 5147 | mm | 1 | depth of cut"));
        assert!(p.contains("| 6023 | mm/min | 5000 |"));
        assert_eq!(cell("a|b"), "a\\|b");
    }

    /// A new catalog code fails here until it has a proof program or a test named
    /// in PROVEN_ELSEWHERE; every code the tables name is a catalog code.
    #[test]
    fn every_catalog_code_is_proven_once() {
        for e in CATALOG {
            let cases = PROOFS.iter().filter(|p| p.code == e.code).count();
            let elsewhere = PROVEN_ELSEWHERE.iter().filter(|x| x.0 == e.code).count();
            assert!(cases > 0 || elsewhere == 1, "alarm {} ({}) is proven by nothing", e.code, e.title);
            assert!(cases == 0 || elsewhere == 0, "alarm {} is proven twice", e.code);
        }
        let in_catalog = |c: u16| CATALOG.iter().any(|e| e.code == c);
        assert!(PROOFS.iter().all(|p| in_catalog(p.code)));
        assert!(PROVEN_ELSEWHERE.iter().all(|x| in_catalog(x.0)));
        for m in MANUAL {
            if let Outcome::Raised(codes) = m.outcome {
                assert!(codes.iter().all(|&c| in_catalog(c)), "{}", m.section);
            }
        }
    }

    #[test]
    fn case_names_are_unique() {
        for (i, p) in PROOFS.iter().enumerate() {
            assert!(PROOFS[..i].iter().all(|q| q.case != p.case), "{}", p.case);
        }
    }
}
