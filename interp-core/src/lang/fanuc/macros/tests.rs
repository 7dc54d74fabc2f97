//! Expressions, statements and macro words through the reader: every operator and
//! precedence case, every function against known values, every null rule and the
//! examples of 2.24.

extern crate std;

use std::format;

use super::statement::loop_mark;
use super::*;
use crate::alarm::AlarmKind::{self, *};
use crate::lang::fanuc::parse::{Block, Statement, read_block, read_statement};
use crate::units::{IncrementSystem, InputMode, Number, NumberFormat, Units};

const METRIC: NumberFormat =
    NumberFormat { units: Units::Metric, input: InputMode::Calculator, increments: IncrementSystem::IsB };

/// A table with `pairs` set.
fn table(pairs: &[(u16, f64)]) -> Variables {
    let mut v = Variables::new();
    for &(n, x) in pairs {
        v.set(n, Some(x)).unwrap();
    }
    v
}

/// Reads a block that must be a macro statement.
fn statement_in(text: &str, vars: &Variables) -> Result<MacroStatement, AlarmKind> {
    match read_statement(text.as_bytes(), 1, vars, &METRIC)? {
        Statement::Macro(m) => Ok(m.statement),
        Statement::Nc(b) => panic!("{text}: read as NC {b:?}"),
        Statement::Call(c, _) => panic!("{text}: read as a call {c:?}"),
    }
}

/// The value `#900=<expr>` assigns.
fn eval_in(expr: &str, vars: &Variables) -> Result<Value, AlarmKind> {
    match statement_in(&format!("#900={expr}"), vars)? {
        MacroStatement::Assign { var: 900, value } => Ok(value),
        other => panic!("{expr}: {other:?}"),
    }
}

/// The number `#900=<expr>` assigns, with no variables set.
fn eval(expr: &str) -> Result<f64, AlarmKind> {
    eval_in(expr, &Variables::new()).map(|v| v.expect("not null"))
}

/// The truth of `IF [cond] GOTO 1`.
fn holds_in(cond: &str, vars: &Variables) -> bool {
    match statement_in(&format!("IF [{cond}] GOTO 1"), vars).unwrap() {
        MacroStatement::Goto { seq: 1 } => true,
        MacroStatement::Nop => false,
        other => panic!("{cond}: {other:?}"),
    }
}

/// Reads an NC block.
fn nc_in(text: &str, vars: &Variables, fmt: &NumberFormat) -> Result<Block, AlarmKind> {
    match read_statement(text.as_bytes(), 1, vars, fmt)? {
        Statement::Nc(b) => Ok(b),
        Statement::Macro(m) => panic!("{text}: read as macro {m:?}"),
        Statement::Call(c, _) => panic!("{text}: read as a call {c:?}"),
    }
}

fn num(mantissa: i64, frac_digits: u8) -> Number {
    Number { mantissa, frac_digits, has_point: true }
}

#[test]
fn arithmetic_operators() {
    assert_eq!(eval("1+2"), Ok(3.0));
    assert_eq!(eval("5-7.5"), Ok(-2.5));
    assert_eq!(eval("2.5*4"), Ok(10.0));
    assert_eq!(eval("7/2"), Ok(3.5));
    assert_eq!(eval("1/3"), Ok(1.0 / 3.0));
    assert_eq!(eval("7 MOD 3"), Ok(1.0));
    assert_eq!(eval("-7MOD3"), Ok(-1.0));
    assert_eq!(eval("-5"), Ok(-5.0));
    assert_eq!(eval("--5"), Ok(5.0));
    assert_eq!(eval("+5"), Ok(5.0));
    assert_eq!(eval("2--3"), Ok(5.0));
    assert_eq!(eval("123"), Ok(123.0), "2.24.1: #1=123 is 123.000");
    assert_eq!(eval(".5"), Ok(0.5));
    assert_eq!(eval("5."), Ok(5.0));
    assert_eq!(eval("0.1+0.2"), Ok(0.1 + 0.2));
    assert_eq!(eval("12 AND 10"), Ok(8.0));
    assert_eq!(eval("12 AN 10"), Ok(8.0));
    assert_eq!(eval("12 OR 10"), Ok(14.0));
    assert_eq!(eval("12 XOR 10"), Ok(6.0));
    let top = table(&[(1, 4_294_967_295.0)]);
    assert_eq!(eval_in("#1 AND 255", &top), Ok(Some(255.0)));
    assert_eq!(eval_in("[#1+1] AND 255", &top), Err(ArgumentOutOfRange { function: "AND/OR/XOR" }));
}

#[test]
fn precedence_follows_the_manual_table() {
    // Level 2 (* / AND MOD) before level 1 (+ - OR XOR), left to right within a level.
    assert_eq!(eval("1+2*3"), Ok(7.0));
    assert_eq!(eval("[1+2]*3"), Ok(9.0));
    assert_eq!(eval("10-4-3"), Ok(3.0));
    assert_eq!(eval("8/4/2"), Ok(1.0));
    assert_eq!(eval("2*3/4"), Ok(1.5));
    assert_eq!(eval("-2*3"), Ok(-6.0));
    assert_eq!(eval("2*-3"), Ok(-6.0));
    assert_eq!(eval("1+6 AND 3"), Ok(3.0), "AND binds like *");
    assert_eq!(eval("5 AND 3+1"), Ok(2.0));
    assert_eq!(eval("2*7 MOD 4"), Ok(2.0));
    assert_eq!(eval("7 MOD 4*2"), Ok(6.0));
    assert_eq!(eval("6-2 XOR 1"), Ok(5.0), "XOR binds like -");
    assert_eq!(eval("1 OR 2+4"), Ok(7.0));
    // Level 3 (functions) and 4 (#) before the operators; 5 (brackets) first.
    assert_eq!(eval("SIN[30]*2+SQRT[16]"), Ok(5.0));
    assert_eq!(eval("SQRT[16]/2"), Ok(2.0));
    assert_eq!(eval_in("#1*2", &table(&[(1, 3.0)])), Ok(Some(6.0)));
    assert_eq!(eval_in("#[#1+1]*2", &table(&[(1, 3.0), (4, 5.0)])), Ok(Some(10.0)));
    assert_eq!(eval("[[[[2]]]]"), Ok(2.0));
    assert_eq!(eval("2*[3+[4-[5*[6/3]]]]"), Ok(-6.0));
}

#[test]
fn functions_against_known_values() {
    for (f, v) in [
        ("SIN[30]", 0.5),
        ("SIN[90]", 1.0),
        ("COS[60]", 0.5),
        ("COS[180]", -1.0),
        ("TAN[45]", 1.0),
        ("TAN[0]", 0.0),
        ("ASIN[0.5]", 30.0),
        ("ASIN[-1]", -90.0),
        ("ACOS[0.5]", 60.0),
        ("ACOS[-1]", 180.0),
        ("ATAN[1]/[1]", 45.0),
        ("ATAN[-1]/[-1]", 45.0),
        ("ATAN[1]", 45.0),
        ("ATAN[3]/[0]", 90.0),
        ("SQRT[16]", 4.0),
        ("SQRT[0]", 0.0),
        ("ABS[-3.5]", 3.5),
        ("ABS[2]", 2.0),
        ("ROUND[1.2345]", 1.0),
        ("ROUND[2.5]", 3.0),
        ("ROUND[-2.5]", -3.0),
        ("FIX[1.2]", 1.0),
        ("FIX[-1.2]", -1.0),
        ("FUP[1.2]", 2.0),
        ("FUP[-1.2]", -2.0),
        ("EXP[0]", 1.0),
        ("MAX[1, 2]", 2.0),
        ("MAX[-1,-2]", -1.0),
        ("MIN[1,2]", 1.0),
        ("MIN[3, 2.5]", 2.5),
    ] {
        assert_eq!(eval(f), Ok(v), "{f}");
    }
    assert!((eval("EXP[1]").unwrap() - core::f64::consts::E).abs() < 1e-15);
    assert!((eval("SIN[60]").unwrap() - 0.866_025_403_784_438_6).abs() < 1e-15);
    assert!((eval("ATAN[1]/[2]").unwrap() - 26.565_051_177_077_99).abs() < 1e-12);
    assert!((eval("ASIN[0.3]").unwrap() - 17.457_603_123_722_095).abs() < 1e-12);
    // The manual's abbreviations mean the same functions; names in any case.
    for (short, long) in [
        ("SI[30]", "SIN[30]"),
        ("AS[0.5]", "ASIN[0.5]"),
        ("CO[60]", "COS[60]"),
        ("AC[0.5]", "ACOS[0.5]"),
        ("TA[45]", "TAN[45]"),
        ("AT[1]/[2]", "ATAN[1]/[2]"),
        ("SQ[2]", "SQRT[2]"),
        ("AB[-2]", "ABS[-2]"),
        ("RO[2.7]", "ROUND[2.7]"),
        ("FI[2.7]", "FIX[2.7]"),
        ("sin[30]", "SIN[30]"),
    ] {
        assert_eq!(eval(short), eval(long), "{short}");
    }
    // ATAN[a]/b without a bracket is ATAN[a] divided by b.
    assert_eq!(eval("ATAN[1]/2"), Ok(22.5));
}

#[test]
fn domain_errors_are_alarms() {
    assert_eq!(eval("1/0"), Err(DivideByZero));
    assert_eq!(eval_in("1/#1", &Variables::new()), Err(DivideByZero), "null divisor is 0");
    assert_eq!(eval("5 MOD 0"), Err(DivideByZero));
    assert_eq!(eval("TAN[90]"), Err(DivideByZero), "2.24.2 (6): TAN[90]");
    assert_eq!(eval("TAN[-270]"), Err(DivideByZero));
    assert_eq!(eval("ASIN[1.5]"), Err(ArgumentOutOfRange { function: "ASIN" }));
    assert_eq!(eval("ACOS[-1.01]"), Err(ArgumentOutOfRange { function: "ACOS" }));
    assert_eq!(eval("SQRT[-1]"), Err(ArgumentOutOfRange { function: "SQRT" }));
    assert_eq!(eval("EXP[81]"), Err(ArgumentOutOfRange { function: "EXP" }));
    assert_eq!(eval("EXP[-80.5]"), Err(ArgumentOutOfRange { function: "EXP" }));
    assert_eq!(eval("ATAN[0]/[0]"), Err(ArgumentOutOfRange { function: "ATAN" }));
    assert_eq!(eval("1.5 AND 1"), Err(ArgumentOutOfRange { function: "AND/OR/XOR" }));
    assert_eq!(eval("-1 OR 1"), Err(ArgumentOutOfRange { function: "AND/OR/XOR" }));
    let big = table(&[(1, 1e200)]);
    assert_eq!(eval_in("#1*#1", &big), Err(MacroOverflow));
    assert_eq!(eval_in("#1*EXP[80]*EXP[80]*EXP[80]*EXP[80]", &big), Err(MacroOverflow));
}

#[test]
fn bracket_nesting_is_limited_to_five_levels() {
    assert_eq!(eval("[[[[[1]]]]]"), Ok(1.0));
    assert_eq!(eval("[[[[[[1]]]]]]"), Err(TooManyBrackets));
    // Function and indirection brackets count.
    assert_eq!(eval("[[[[SIN[30]]]]]"), Ok(0.5));
    assert_eq!(eval("[[[[[SIN[30]]]]]]"), Err(TooManyBrackets));
    let v = table(&[(1, 2.0), (2, 7.0)]);
    assert_eq!(eval_in("[[[[#[#1]]]]]", &v), Ok(Some(7.0)));
    assert_eq!(eval_in("[[[[[#[#1]]]]]]", &v), Err(TooManyBrackets));
    // IF's condition bracket is the first level.
    assert_eq!(statement_in("IF [[[[[1]]]] EQ 1] GOTO 5", &v), Ok(MacroStatement::Goto { seq: 5 }));
    assert_eq!(statement_in("IF [[[[[[1]]]]] EQ 1] GOTO 5", &v), Err(TooManyBrackets));
    // Any number of signs, no recursion.
    let signs = format!("#1={}1", "-".repeat(10_000));
    assert_eq!(statement_in(&signs, &v), Ok(MacroStatement::Assign { var: 1, value: Some(1.0) }));
}

#[test]
fn format_errors() {
    for (text, what) in [
        ("#1=", "expression ends too early"),
        ("#1=[1+2", "']' expected"),
        ("#1=FOO[1]", "unknown function or operator"),
        ("#1=SIN 30", "a function needs its argument in [ ]"),
        ("#1=MAX[1]", "MAX/MIN need two arguments [a, b]"),
        ("#1=1+*2", "operand expected"),
        ("#1=1.2.3", "second decimal point in a constant"),
        ("#1 5", "'=' expected after the variable"),
        ("#=5", "'#' needs a variable number"),
        ("#1=[1 GT 0]", "a comparison where a number is needed"),
        ("#1=[1 GT 0]+1", "a comparison where a number is needed"),
        ("#1=[[1 GT 0] AND 1]", "AND/OR/XOR between a condition and a number"),
        ("#1=1234567890", "constant with more than 9 digits before or after the point"),
        ("IF [#1] GOTO 5", "the condition needs EQ, NE, GT, GE, LT or LE"),
        ("IF #1 EQ 1 GOTO 5", "the condition must be in [ ]"),
        ("IF [#1 EQ 1] #2=1", "IF […] needs GOTO or THEN"),
        ("WHILE [#1 LT 1] END 1", "WHILE […] needs DO m"),
        ("DO", "DO and END need a loop number 1-3"),
        ("THEN #1=1", "THEN without IF"),
        ("#1=1 $", "unexpected text after the statement"),
    ] {
        assert_eq!(statement_in(text, &Variables::new()), Err(MacroFormat { what }), "{text}");
    }
}

#[test]
fn null_rules_of_2_24_1() {
    let v = Variables::new(); // #2 null
    // #1=#2 → null; #1=#2*3 → 0; #1=#2+#2 → 0.
    assert_eq!(eval_in("#2", &v), Ok(None));
    assert_eq!(eval_in("#2*3", &v), Ok(Some(0.0)));
    assert_eq!(eval_in("#2+#2", &v), Ok(Some(0.0)));
    assert_eq!(eval_in("[#2]", &v), Ok(None), "brackets are no operation");
    assert_eq!(eval_in("-#2", &v), Ok(Some(0.0)), "a sign is an operation");
    assert_eq!(eval_in("SIN[#2]", &v), Ok(Some(0.0)));
    assert_eq!(eval_in("#0", &v), Ok(None));
    // #2 null: EQ, GE, LE against #0 hold, the others do not.
    for (op, holds) in [("EQ", true), ("GE", true), ("LE", true), ("NE", false), ("GT", false), ("LT", false)] {
        assert_eq!(holds_in(&format!("#2 {op} #0"), &v), holds, "null {op} null");
    }
    // #2 = 0: only NE against #0 holds.
    let zero = table(&[(2, 0.0)]);
    for (op, holds) in [("EQ", false), ("GE", false), ("LE", false), ("NE", true), ("GT", false), ("LT", false)] {
        assert_eq!(holds_in(&format!("#2 {op} #0"), &zero), holds, "0 {op} null");
    }
    // Note 6: in + - * inside a condition null is 0.
    assert!(holds_in("#2+0 EQ 0", &v));
    assert!(!holds_in("#2 EQ 0", &v));
    // #0 cannot be written.
    assert_eq!(statement_in("#0=1", &v), Err(WriteProtectedVariable { number: 0 }));
    assert_eq!(statement_in("#[#2]=1", &v), Err(WriteProtectedVariable { number: 0 }), "null index is #0");
}

#[test]
fn comparisons_in_both_spellings() {
    let v = table(&[(1, 2.0), (2, 3.0)]);
    for (cond, holds) in [
        ("#1 EQ 2", true),
        ("#1 == 2", true),
        ("#1 NE 2", false),
        ("#1 <> 3", true),
        ("#1 GT #2", false),
        ("#2 > #1", true),
        ("#1 GE 2", true),
        ("#1 >= 2.5", false),
        ("#1 LT #2", true),
        ("#1 < 2", false),
        ("#1 LE 2", true),
        ("#2 <= 2", false),
        ("#1*2 GT #2", true),
        ("#1 eq 2", true),
        ("#1EQ2", true),
        ("[#1 EQ 2] AND [#2 EQ 3]", true),
        ("[#1 EQ 2] AND [#2 EQ 4]", false),
        ("[#1 EQ 1] OR [#2 EQ 3]", true),
        ("[#1 EQ 2] XOR [#2 EQ 3]", false),
    ] {
        assert_eq!(holds_in(cond, &v), holds, "{cond}");
    }
}

#[test]
fn variables_and_indirection() {
    // 2.24.1: #[#20+#30/4]; #[#30] stands for #5 when #30 = 5.
    let v = table(&[(20, 2.0), (30, 5.0), (5, 55.0), (3, 33.0)]);
    assert_eq!(eval_in("#[#30]", &v), Ok(Some(55.0)));
    assert_eq!(eval_in("#[#20+#30/4]", &v), Ok(Some(33.0)), "#[3.25] is #3");
    assert_eq!(eval_in("#999", &v), Ok(None));
    assert_eq!(eval_in("#1000", &v), Err(VariableNumberOutOfRange { number: 1000 }));
    assert_eq!(eval_in("#[-1]", &v), Err(VariableNumberOutOfRange { number: -1 }));
    assert_eq!(statement_in("#[#30*2]=4", &v), Ok(MacroStatement::Assign { var: 10, value: Some(4.0) }));
    assert_eq!(statement_in("#1000=4", &v), Err(VariableNumberOutOfRange { number: 1000 }));
    assert_eq!(statement_in("# 7 = # 30", &v), Ok(MacroStatement::Assign { var: 7, value: Some(5.0) }));
}

#[test]
fn control_statements() {
    use MacroStatement::*;
    let v = table(&[(1, 10.0), (2, 3.0), (3, 3.0)]);
    assert_eq!(statement_in("GOTO 10", &v), Ok(Goto { seq: 10 }));
    assert_eq!(statement_in("GOTO#1", &v), Ok(Goto { seq: 10 }));
    assert_eq!(statement_in("GOTO [#1*2+1]", &v), Ok(Goto { seq: 21 }));
    assert_eq!(statement_in("GOTO 99999", &v), Ok(Goto { seq: 99_999 }));
    for bad in ["GOTO 0", "GOTO 100000", "GOTO 1.5", "GOTO #9", "GOTO -5"] {
        assert_eq!(statement_in(bad, &v), Err(SequenceOutOfRange), "{bad}");
    }
    assert_eq!(statement_in("IF [#1 GT 5] GOTO 20", &v), Ok(Goto { seq: 20 }));
    assert_eq!(statement_in("IF [#1 LT 5] GOTO 20", &v), Ok(Nop));
    // 2.24.2 example: IF[#2 EQ #3] THEN #4=0.
    assert_eq!(statement_in("IF[#2 EQ #3] THEN #4=0", &v), Ok(Assign { var: 4, value: Some(0.0) }));
    // A false IF does not evaluate its THEN or GOTO part (no alarm), only reads it.
    assert_eq!(statement_in("IF [#1 EQ 0] THEN #4=1/0", &v), Ok(Nop));
    assert_eq!(statement_in("IF [#1 EQ 0] GOTO [1/0]", &v), Ok(Nop));
    assert_eq!(statement_in("IF [#1 EQ 0] GOTO 0", &v), Ok(Nop));
    assert_eq!(statement_in("IF [#1 EQ 0] THEN #4=[1", &v), Err(MacroFormat { what: "']' expected" }));
    assert_eq!(statement_in("IF [#1 EQ 10] THEN #4=1/0", &v), Err(DivideByZero));
    assert_eq!(statement_in("WHILE [#1 GT 0] DO 1", &v), Ok(Loop { label: 1, enter: true }));
    assert_eq!(statement_in("WHILE[#1 LE 0]DO3", &v), Ok(Loop { label: 3, enter: false }));
    assert_eq!(statement_in("DO2", &v), Ok(Loop { label: 2, enter: true }));
    assert_eq!(statement_in("END 2", &v), Ok(End { label: 2 }));
    assert_eq!(statement_in("while [#1 gt 0] do 1", &v), Ok(Loop { label: 1, enter: true }));
    for bad in ["DO 4", "END 0", "WHILE [1 EQ 1] DO 9"] {
        assert!(matches!(statement_in(bad, &v), Err(IllegalLoopNumber { .. })), "{bad}");
    }
}

#[test]
fn sequence_number_and_skip_mark_before_a_macro_statement() {
    let v = Variables::new();
    let Statement::Macro(m) = read_statement(b"/2 N10 #1=5 (comment)", 7, &v, &METRIC).unwrap() else { panic!() };
    assert_eq!((m.line, m.skip_level, m.seq), (7, Some(2), Some(10)));
    assert_eq!(m.statement, MacroStatement::Assign { var: 1, value: Some(5.0) });
    let Statement::Macro(m) = read_statement(b"N20 WHILE [1 EQ 1] DO1", 1, &v, &METRIC).unwrap() else { panic!() };
    assert_eq!(m.seq, Some(20));
}

#[test]
fn macro_and_nc_words_may_not_share_a_block() {
    let v = Variables::new();
    for text in ["#1=5 G01", "G01 X1 #1=5", "G01 X1 IF [1 EQ 1] GOTO 5", "N10 G00 GOTO 5", "GOTO 5 X1", "#1=1 N5"] {
        assert_eq!(read_statement(text.as_bytes(), 1, &v, &METRIC), Err(MacroAndNcInOneBlock), "{text}");
    }
}

#[test]
fn address_substitution_examples_of_2_24_1() {
    let v = table(&[(203, 15.0), (210, 250.0), (230, 3.0), (1, 2.0)]);
    let b = nc_in("G#230 F#203 Z-#210 X[#1*2]", &v, &METRIC).unwrap();
    assert_eq!(b.g.as_slice(), &[30], "G#230 is G3");
    assert_eq!(b.get(b'F'), Some(num(15, 0)));
    assert_eq!(b.get(b'Z'), Some(num(-250, 0)));
    assert_eq!(b.get(b'X'), Some(num(4, 0)));
    let b = nc_in("F[25.4/10] X - [#1] Z+#1", &v, &METRIC).unwrap();
    assert_eq!(b.get(b'F'), Some(num(254, 2)), "'/' inside brackets divides");
    assert_eq!(b.get(b'X'), Some(num(-2, 0)));
    assert_eq!(b.get(b'Z'), Some(num(2, 0)));
    // 2.24.1: #1=1.23456; the word keeps 9 decimals, checking rounds it to 1.235.
    let b = nc_in("X#1", &table(&[(1, 1.23456)]), &METRIC).unwrap();
    assert_eq!(b.get(b'X'), Some(num(123456, 5)));
    assert_eq!(METRIC.length_nm(&b.get(b'X').unwrap()), Some(1_235_000));
    // Outside brackets '/' is still a block skip mark, so it cannot follow a word.
    assert_eq!(nc_in("X#1/2", &v, &METRIC), Err(MisplacedBlockSkip));
}

#[test]
fn integer_addresses_get_whole_numbers_from_macro_values() {
    let v = table(&[(1, 3.0), (2, 3.4), (3, 101.0), (4, 800.6), (5, 12.0), (6, -3.0), (7, 2.1)]);
    let b = nc_in("M#1 T#3 S#4 P#5", &v, &METRIC).unwrap();
    assert_eq!(b.m.as_slice(), &[3]);
    assert_eq!(b.get(b'T'), Some(Number::int(101)));
    assert_eq!(b.get(b'S'), Some(Number::int(801)));
    assert_eq!(b.get(b'P'), Some(Number::int(12)));
    assert_eq!(nc_in("M#2", &v, &METRIC).unwrap().m.as_slice(), &[3]);
    assert_eq!(nc_in("G#7", &v, &METRIC).unwrap().g.as_slice(), &[21]);
    assert_eq!(nc_in("M#6", &v, &METRIC), Err(IllegalMinusSign { letter: b'M' }));
    assert_eq!(nc_in("N#1", &v, &METRIC), Err(MacroFormat { what: "N and O take no variables" }));
    assert_eq!(nc_in("X[1e]", &v, &METRIC), Err(MacroFormat { what: "']' expected" }));
    assert_eq!(nc_in("X[1 GT 0]", &v, &METRIC), Err(MacroFormat { what: "a comparison where a number is needed" }));
    let huge = table(&[(1, 1e12)]);
    assert_eq!(nc_in("X#1", &huge, &METRIC), Err(TooManyDigits { letter: b'X' }));
    assert_eq!(nc_in("M#1", &huge, &METRIC), Err(TooManyDigits { letter: b'M' }));
}

#[test]
fn a_null_variable_drops_its_word() {
    // 2.24.1: #10 = 0, #11 null: G00 X#10 Y#11 is G00 X0.
    let v = table(&[(10, 0.0)]);
    let b = nc_in("G00 X#10 Y#11", &v, &METRIC).unwrap();
    assert_eq!(b.g.as_slice(), &[0]);
    assert_eq!(b.get(b'X'), Some(num(0, 0)));
    assert!(!b.has(b'Y'));
    let b = nc_in("X-#11 Z[#11] U[#11+1] M#11 ,C#11", &v, &METRIC).unwrap();
    assert_eq!(b.letters().collect::<heapless::Vec<u8, 4>>().as_slice(), b"U");
    assert!(b.m.is_empty() && b.chamfer.is_none());
    // All words null: the G code alone remains, as if the words were not written.
    let b = nc_in("G01 X#1 Z#2", &v, &METRIC).unwrap();
    assert_eq!((b.g.as_slice(), b.letters().count()), (&[10][..], 0));
}

#[test]
fn round_in_a_word_rounds_to_the_least_increment_and_in_a_statement_to_a_whole_number() {
    // 2.24.2 (7): #2=ROUND[#3] with #3 = 1.2345 gives 1.
    let v = table(&[(1, 1.2345), (2, 2.3456), (3, 1.2345)]);
    assert_eq!(eval_in("ROUND[#3]", &v), Ok(Some(1.0)));
    // In an NC word: 1.2345 → 1.235 (IS-B metric); sums of rounded values add up
    // (FANUC's example: X-[ROUND[#1]+ROUND[#2]] returns the tool exactly).
    let b = nc_in("X[ROUND[#1]] Z-[ROUND[#1]+ROUND[#2]] U[#1+#2]", &v, &METRIC).unwrap();
    assert_eq!(b.get(b'X'), Some(num(1235, 3)));
    assert_eq!(b.get(b'Z'), Some(num(-3581, 3)));
    assert_eq!(METRIC.length_nm(&b.get(b'U').unwrap()), Some(3_580_000), "1.2345+2.3456 = 3.5801");
    let inch = NumberFormat { units: Units::Inch, ..METRIC };
    assert_eq!(nc_in("X[ROUND[#1*0.1]]", &v, &inch).unwrap().get(b'X'), Some(num(1235, 4)), "0.0001 in");
    let isc = NumberFormat { increments: IncrementSystem::IsC, ..METRIC };
    assert_eq!(nc_in("X[ROUND[#2+0.00005]]", &v, &isc).unwrap().get(b'X'), Some(num(23457, 4)), "0.0001 mm");
    assert_eq!(nc_in("C[ROUND[12.34567]]", &v, &inch).unwrap().get(b'C'), Some(num(12346, 3)), "0.001 deg");
}

#[test]
fn read_block_rejects_what_needs_variables() {
    assert!(read_block(b"G00 X[1+2]", 1).is_ok());
    assert_eq!(
        read_block(b"G00 X#1", 1),
        Err(MacroFormat { what: "variables are not available here (use read_statement)" })
    );
    assert_eq!(read_block(b"#1=2", 1), Err(MacroFormat { what: "macro statement (use read_statement)" }));
    assert!(matches!(read_block(b"G00 X[ROUND[1]]", 1), Err(MacroFormat { .. })));
}

#[test]
fn loop_marks_are_found_without_evaluating() {
    use super::statement::LoopMark;
    assert_eq!(loop_mark(b"N10 WHILE [#1/0 LT [2]] DO 2 (x)"), Some(LoopMark::Do(2)));
    assert_eq!(loop_mark(b"/ DO1"), Some(LoopMark::Do(1)));
    assert_eq!(loop_mark(b"END 3"), Some(LoopMark::End(3)));
    assert_eq!(loop_mark(b"END 7"), Some(LoopMark::End(0)));
    assert_eq!(loop_mark(b"G01 X1"), None);
    assert_eq!(loop_mark(b"#1=1"), None);
    assert_eq!(loop_mark(b"IF [1 EQ 1] GOTO 1"), None);
}

#[test]
fn read_statement_gives_a_call_block_with_its_arguments() {
    use crate::lang::fanuc::calls::{Caller, MacroCall};
    let vars = Variables::new();
    let Ok(Statement::Call(c, args)) = read_statement(b"N7 G65 P9100 L2 A1. B-2.5", 3, &vars, &METRIC) else {
        panic!("not read as a call");
    };
    assert_eq!((c.line, c.seq), (3, Some(7)));
    assert_eq!(c.call, MacroCall::Simple { program: 9100, repeats: 2, by: Caller::Program });
    assert_eq!(args.defined().collect::<std::vec::Vec<_>>(), [(1, 1.0), (2, -2.5)]);
    // Without P: alarm 0076, from the call path as from the interpreter.
    assert_eq!(read_statement(b"G65 A1.", 1, &vars, &METRIC).map_err(|k| k.code()).err(), Some(76));
}
