//! An interpreter of the Aseba language's 16-bit integer semantics, for the subset the kit's
//! generator emits: it parses the program text and runs its initialisation and event
//! handlers, so that the fixed-point outputs written into the kit (`golden.csv`) and checked by
//! the tests are those of the program itself, not of a parallel model of it.
//!
//! Semantics (Aseba's `vm.c`, `natives.c` and compiler, as docs/robots-sources.md §2.3 quotes
//! them): one type, signed 16 bits; `+ - * << >> & | ^` wrap (two's complement); `/` and `%`
//! truncate toward 0 (C), and a division or modulo by 0 stops the VM; the compiler folds
//! constant expressions in C `int` (no wrap inside them) and rewrites `x / 2^k` (a constant
//! positive power of two, `k ≥ 0`) into `x >> k`, which floors; array indices are checked
//! (out of range stops the VM); `math.muldiv` multiplies in 32 bits and truncates the
//! quotient to 16 bits; `math.dot` adds the products in 32 bits and shifts right.
//!
//! Supported: `var` (scalars and arrays, with literal or array-constructor initialisers),
//! assignments to scalars and array elements, `if/elseif/else`, `while`, `for … in a:b`
//! (step 1), `sub`/`callsub`, `return`, `onevent`, `call math.{copy,fill,clamp,muldiv,dot,mul,
//! min,max}` with whole arrays, constant-index elements, constant slices `a[i:j]` or
//! expressions as arguments, `abs`, unary `-`, comparisons with `and`/`or`/`not`, `emit` of a
//! variable (recorded).
//!
//! The interpreter counts the VM's steps as the instructions the Aseba compiler emits for each
//! construct (one step per bytecode instruction, as `AsebaDebugBareRun` counts them): a
//! load, an immediate, an operator, a store, a conditional branch, a jump, an argument pushed
//! to a native and the native call itself are one step each. The compiler's optimiser only
//! removes instructions, so the counts are upper estimates of the real ones.

use std::collections::HashMap;
use std::rc::Rc;

/// Why a program cannot be parsed or stopped while running.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub(crate) enum AsebaError {
    /// The text is not in the supported subset.
    #[error("parse error at token {at}: {message}")]
    Parse {
        /// Index of the offending token.
        at: usize,
        /// What was wrong.
        message: String,
    },
    /// The VM would stop (division by zero, index out of range, unknown name …).
    #[error("the VM stops: {0}")]
    Stopped(String),
}

type Res<T> = Result<T, AsebaError>;

fn stop<T>(message: impl Into<String>) -> Res<T> {
    Err(AsebaError::Stopped(message.into()))
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Num(i64),
    Name(String),
    Sym(&'static str),
}

const SYMS: [&str; 22] = [
    "==", "!=", "<=", ">=", "<<", ">>", "<", ">", "=", "+", "-", "*", "/", "%", "&", "|", "^", "(",
    ")", "[", "]", ",",
];

fn lex(text: &str) -> Res<Vec<Tok>> {
    let chars: Vec<char> = text.chars().collect();
    let mut toks = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c == '#' && chars.get(i + 1) == Some(&'*') {
            let close = (i + 2..chars.len().saturating_sub(1))
                .find(|&j| chars[j] == '*' && chars[j + 1] == '#');
            i = close.map_or(chars.len(), |j| j + 2);
        } else if c == '#' {
            i = (i..chars.len())
                .find(|&j| chars[j] == '\n')
                .unwrap_or(chars.len());
        } else if c.is_ascii_digit() {
            let start = i;
            while i < chars.len() && chars[i].is_ascii_digit() {
                i += 1;
            }
            let digits: String = chars[start..i].iter().collect();
            let v = digits.parse::<i64>().map_err(|e| AsebaError::Parse {
                at: toks.len(),
                message: e.to_string(),
            })?;
            toks.push(Tok::Num(v));
        } else if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || "_.".contains(chars[i])) {
                i += 1;
            }
            toks.push(Tok::Name(chars[start..i].iter().collect()));
        } else if c == ':' {
            toks.push(Tok::Sym(":"));
            i += 1;
        } else {
            let rest: String = chars[i..(i + 2).min(chars.len())].iter().collect();
            let Some(sym) = SYMS.iter().find(|s| rest.starts_with(**s)) else {
                return Err(AsebaError::Parse {
                    at: toks.len(),
                    message: format!("unexpected character {c:?}"),
                });
            };
            toks.push(Tok::Sym(sym));
            i += sym.len();
        }
    }
    Ok(toks)
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Op {
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Shl,
    Shr,
    And,
    Or,
    Xor,
}

#[derive(Debug, Clone, PartialEq)]
enum Expr {
    Num(i64),
    Var(String),
    Index(String, Box<Expr>),
    Neg(Box<Expr>),
    Abs(Box<Expr>),
    Bin(Op, Box<Expr>, Box<Expr>),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Cmp {
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

#[derive(Debug, Clone, PartialEq)]
enum Cond {
    Cmp(Cmp, Expr, Expr),
    And(Box<Cond>, Box<Cond>),
    Or(Box<Cond>, Box<Cond>),
    Not(Box<Cond>),
}

#[derive(Debug, Clone, PartialEq)]
enum Arg {
    /// A variable's elements `lo..=hi` (the whole variable, an element or a constant slice).
    Mem(String, Option<(Expr, Expr)>),
    /// An expression, evaluated into a temporary.
    Value(Expr),
}

#[derive(Debug, Clone, PartialEq)]
enum Stmt {
    Assign(String, Option<Expr>, Expr),
    If(Vec<(Cond, Vec<Stmt>)>, Vec<Stmt>),
    While(Cond, Vec<Stmt>),
    For(String, Expr, Expr, Vec<Stmt>),
    Call(String, Vec<Arg>),
    CallSub(String),
    Return,
    /// `emit NAME VAR`: the event with the variable's words.
    Emit(String, String),
}

/// A declared variable: its name, size and initialiser.
#[derive(Debug, Clone, PartialEq)]
struct Decl {
    name: String,
    size: usize,
    init: Option<Vec<Expr>>,
}

/// A parsed program.
#[derive(Debug, Clone, PartialEq, Default)]
struct Program {
    decls: Vec<Decl>,
    init: Vec<Stmt>,
    subs: HashMap<String, Vec<Stmt>>,
    events: HashMap<String, Vec<Stmt>>,
}

struct Parser<'a> {
    toks: &'a [Tok],
    at: usize,
    consts: &'a HashMap<String, i64>,
}

fn is_block_end(t: Option<&Tok>) -> bool {
    match t {
        None => true,
        Some(Tok::Name(n)) => ["end", "else", "elseif", "sub", "onevent"].contains(&n.as_str()),
        _ => false,
    }
}

impl<'a> Parser<'a> {
    fn err<T>(&self, message: impl Into<String>) -> Res<T> {
        Err(AsebaError::Parse {
            at: self.at,
            message: message.into(),
        })
    }

    fn peek(&self) -> Option<&'a Tok> {
        self.toks.get(self.at)
    }

    fn peek_sym(&self, s: &str) -> bool {
        matches!(self.peek(), Some(Tok::Sym(t)) if *t == s)
    }

    fn peek_word(&self, w: &str) -> bool {
        matches!(self.peek(), Some(Tok::Name(n)) if n == w)
    }

    fn sym(&mut self, s: &str) -> Res<()> {
        if self.peek_sym(s) {
            self.at += 1;
            Ok(())
        } else {
            self.err(format!("expected {s:?}, found {:?}", self.peek()))
        }
    }

    fn word(&mut self, w: &str) -> Res<()> {
        if self.peek_word(w) {
            self.at += 1;
            Ok(())
        } else {
            self.err(format!("expected {w:?}, found {:?}", self.peek()))
        }
    }

    fn name(&mut self) -> Res<String> {
        match self.peek() {
            Some(Tok::Name(n)) => {
                self.at += 1;
                Ok(n.clone())
            }
            t => self.err(format!("expected a name, found {t:?}")),
        }
    }

    fn program(&mut self) -> Res<Program> {
        let mut p = Program::default();
        while self.peek_word("var") {
            self.at += 1;
            p.decls.push(self.decl()?);
        }
        p.init = self.block()?;
        while let Some(Tok::Name(kw)) = self.peek() {
            let kw = kw.clone();
            self.at += 1;
            let name = self.name()?;
            let body = self.block()?;
            match kw.as_str() {
                "sub" => p.subs.insert(name, body),
                "onevent" => p.events.insert(name, body),
                _ => return self.err(format!("unexpected {kw:?}")),
            };
        }
        match self.peek() {
            None => Ok(p),
            t => self.err(format!("unexpected {t:?} at top level")),
        }
    }

    fn decl(&mut self) -> Res<Decl> {
        let name = self.name()?;
        let mut size = 1;
        if self.peek_sym("[") {
            self.at += 1;
            let e = self.expr()?;
            size = usize::try_from(fold(&e).unwrap_or(-1))
                .or_else(|_| self.err("array size must be a constant"))?;
            self.sym("]")?;
        }
        let mut init = None;
        if self.peek_sym("=") {
            self.at += 1;
            init = Some(if self.peek_sym("[") {
                self.at += 1;
                let mut items = vec![self.expr()?];
                while self.peek_sym(",") {
                    self.at += 1;
                    items.push(self.expr()?);
                }
                self.sym("]")?;
                items
            } else {
                vec![self.expr()?]
            });
        }
        if init.as_ref().is_some_and(|v| v.len() != size) {
            return self.err(format!("{name}: initialiser size is not {size}"));
        }
        Ok(Decl { name, size, init })
    }

    fn block(&mut self) -> Res<Vec<Stmt>> {
        let mut out = Vec::new();
        while !is_block_end(self.peek()) {
            out.push(self.stmt()?);
        }
        Ok(out)
    }

    fn stmt(&mut self) -> Res<Stmt> {
        let kw = self.name()?;
        match kw.as_str() {
            "if" => self.if_stmt(),
            "while" => {
                let c = self.cond()?;
                self.word("do")?;
                let body = self.block()?;
                self.word("end")?;
                Ok(Stmt::While(c, body))
            }
            "for" => {
                let var = self.name()?;
                self.word("in")?;
                let (lo, hi) = (self.expr()?, self.range_end()?);
                self.word("do")?;
                let body = self.block()?;
                self.word("end")?;
                Ok(Stmt::For(var, lo, hi, body))
            }
            "call" => {
                let f = self.name()?;
                self.sym("(")?;
                let mut args = vec![self.arg()?];
                while self.peek_sym(",") {
                    self.at += 1;
                    args.push(self.arg()?);
                }
                self.sym(")")?;
                Ok(Stmt::Call(f, args))
            }
            "callsub" => Ok(Stmt::CallSub(self.name()?)),
            "emit" => Ok(Stmt::Emit(self.name()?, self.name()?)),
            "return" => Ok(Stmt::Return),
            _ => {
                let index = if self.peek_sym("[") {
                    self.at += 1;
                    let e = self.expr()?;
                    self.sym("]")?;
                    Some(e)
                } else {
                    None
                };
                self.sym("=")?;
                Ok(Stmt::Assign(kw, index, self.expr()?))
            }
        }
    }

    fn range_end(&mut self) -> Res<Expr> {
        self.sym(":")?;
        self.expr()
    }

    fn if_stmt(&mut self) -> Res<Stmt> {
        let mut arms = Vec::new();
        let mut otherwise = Vec::new();
        loop {
            let c = self.cond()?;
            self.word("then")?;
            arms.push((c, self.block()?));
            if self.peek_word("elseif") {
                self.at += 1;
                continue;
            }
            if self.peek_word("else") {
                self.at += 1;
                otherwise = self.block()?;
            }
            self.word("end")?;
            return Ok(Stmt::If(arms, otherwise));
        }
    }

    fn arg(&mut self) -> Res<Arg> {
        let start = self.at;
        if let Some(Tok::Name(n)) = self.peek() {
            let n = n.clone();
            if !self.consts.contains_key(&n) && n != "abs" {
                self.at += 1;
                if !self.peek_sym("[") {
                    if self.peek_sym(",") || self.peek_sym(")") {
                        return Ok(Arg::Mem(n, None));
                    }
                } else {
                    self.at += 1;
                    let lo = self.expr()?;
                    let hi = if self.peek_sym(":") {
                        self.range_end()?
                    } else {
                        lo.clone()
                    };
                    self.sym("]")?;
                    if self.peek_sym(",") || self.peek_sym(")") {
                        return Ok(Arg::Mem(n, Some((lo, hi))));
                    }
                }
                self.at = start;
            }
        }
        Ok(Arg::Value(self.expr()?))
    }

    fn cond(&mut self) -> Res<Cond> {
        let mut c = self.and_cond()?;
        while self.peek_word("or") {
            self.at += 1;
            c = Cond::Or(Box::new(c), Box::new(self.and_cond()?));
        }
        Ok(c)
    }

    fn and_cond(&mut self) -> Res<Cond> {
        let mut c = self.not_cond()?;
        while self.peek_word("and") {
            self.at += 1;
            c = Cond::And(Box::new(c), Box::new(self.not_cond()?));
        }
        Ok(c)
    }

    fn not_cond(&mut self) -> Res<Cond> {
        if self.peek_word("not") {
            self.at += 1;
            return Ok(Cond::Not(Box::new(self.not_cond()?)));
        }
        let a = self.expr()?;
        let op = match self.peek() {
            Some(Tok::Sym("==")) => Cmp::Eq,
            Some(Tok::Sym("!=")) => Cmp::Ne,
            Some(Tok::Sym("<")) => Cmp::Lt,
            Some(Tok::Sym("<=")) => Cmp::Le,
            Some(Tok::Sym(">")) => Cmp::Gt,
            Some(Tok::Sym(">=")) => Cmp::Ge,
            t => return self.err(format!("expected a comparison, found {t:?}")),
        };
        self.at += 1;
        Ok(Cond::Cmp(op, a, self.expr()?))
    }

    /// Binary operators by precedence level, loosest first (Aseba's table).
    const LEVELS: [&'static [(&'static str, Op)]; 6] = [
        &[("|", Op::Or)],
        &[("^", Op::Xor)],
        &[("&", Op::And)],
        &[("<<", Op::Shl), (">>", Op::Shr)],
        &[("+", Op::Add), ("-", Op::Sub)],
        &[("*", Op::Mul), ("/", Op::Div), ("%", Op::Mod)],
    ];

    fn expr(&mut self) -> Res<Expr> {
        self.level(0)
    }

    fn level(&mut self, k: usize) -> Res<Expr> {
        if k == Self::LEVELS.len() {
            return self.unary();
        }
        let mut e = self.level(k + 1)?;
        'more: loop {
            for (s, op) in Self::LEVELS[k] {
                if self.peek_sym(s) {
                    self.at += 1;
                    e = Expr::Bin(*op, Box::new(e), Box::new(self.level(k + 1)?));
                    continue 'more;
                }
            }
            return Ok(e);
        }
    }

    fn unary(&mut self) -> Res<Expr> {
        match self.peek() {
            Some(Tok::Sym("-")) => {
                self.at += 1;
                Ok(Expr::Neg(Box::new(self.unary()?)))
            }
            Some(Tok::Sym("(")) => {
                self.at += 1;
                let e = self.expr()?;
                self.sym(")")?;
                Ok(e)
            }
            Some(Tok::Num(v)) => {
                self.at += 1;
                Ok(Expr::Num(*v))
            }
            Some(Tok::Name(n)) if n == "abs" => {
                self.at += 1;
                Ok(Expr::Abs(Box::new(self.unary()?)))
            }
            Some(Tok::Name(n)) => {
                self.at += 1;
                if let Some(&v) = self.consts.get(n) {
                    return Ok(Expr::Num(v));
                }
                if self.peek_sym("[") {
                    self.at += 1;
                    let i = self.expr()?;
                    self.sym("]")?;
                    return Ok(Expr::Index(n.clone(), Box::new(i)));
                }
                Ok(Expr::Var(n.clone()))
            }
            t => self.err(format!("expected an expression, found {t:?}")),
        }
    }
}

/// The value of a constant expression, folded in C `int` as the compiler does (`None` if it
/// reads a variable).
fn fold(e: &Expr) -> Option<i64> {
    match e {
        Expr::Num(v) => Some(*v),
        Expr::Var(_) | Expr::Index(..) => None,
        Expr::Neg(a) => fold(a).map(|v| -v),
        Expr::Abs(a) => fold(a).map(i64::abs),
        Expr::Bin(op, a, b) => {
            let (a, b) = (fold(a)?, fold(b)?);
            let (a32, b32) = (a as i32, b as i32);
            Some(i64::from(match op {
                Op::Add => a32.wrapping_add(b32),
                Op::Sub => a32.wrapping_sub(b32),
                Op::Mul => a32.wrapping_mul(b32),
                Op::Div | Op::Mod if b32 == 0 => return None,
                Op::Div => a32.wrapping_div(b32),
                Op::Mod => a32.wrapping_rem(b32),
                Op::Shl => a32.wrapping_shl(b32 as u32),
                Op::Shr => a32.wrapping_shr(b32 as u32),
                Op::And => a32 & b32,
                Op::Or => a32 | b32,
                Op::Xor => a32 ^ b32,
            }))
        }
    }
}

/// A positive power of two `2^k` → `k` (the compiler's `isPOT`/`shiftFromPOT`).
fn power_of_two(v: i64) -> Option<u32> {
    (v > 0 && (v & (v - 1)) == 0).then(|| v.trailing_zeros())
}

/// Whether an immediate needs the two-word form (outside the 12-bit small immediate).
fn large(v: i64) -> bool {
    !(-2048..=2047).contains(&v)
}

/// A program loaded into a VM: its memory (the target's variables first, then the program's),
/// run event by event.
#[derive(Debug, Clone)]
pub(crate) struct Machine {
    program: Rc<Program>,
    mem: Vec<i16>,
    vars: HashMap<String, (usize, usize)>,
    user_words: usize,
    steps: usize,
    emitted: Vec<(String, Vec<i16>)>,
}

/// How a statement list ended: normally, or by `return`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Flow {
    Next,
    Return,
}

/// Steps after which the interpreter gives up on an event (a runaway loop).
const STEP_CAP: usize = 10_000_000;

impl Machine {
    /// Parse `code` with the named constants `consts` (as an .aesl's `<constant>`s) for a
    /// target whose own variables are `target_vars` (name, size); user variables start filled
    /// with a junk value (the VM does not clear them), so a program reading one it never set
    /// shows it.
    pub(crate) fn load(
        code: &str,
        consts: &[(String, i64)],
        target_vars: &[(&str, usize)],
    ) -> Res<Machine> {
        let toks = lex(code)?;
        let consts: HashMap<String, i64> = consts.iter().cloned().collect();
        let program = Parser {
            toks: &toks,
            at: 0,
            consts: &consts,
        }
        .program()?;
        let mut vars = HashMap::new();
        let mut mem = Vec::new();
        for &(name, size) in target_vars {
            vars.insert(name.to_string(), (mem.len(), size));
            mem.resize(mem.len() + size, 0);
        }
        let target_words = mem.len();
        for d in &program.decls {
            if vars.insert(d.name.clone(), (mem.len(), d.size)).is_some() {
                return stop(format!("{} declared twice", d.name));
            }
            mem.resize(mem.len() + d.size, -21846);
        }
        Ok(Machine {
            user_words: mem.len() - target_words,
            program: Rc::new(program),
            mem,
            vars,
            steps: 0,
            emitted: Vec::new(),
        })
    }

    /// Words of the program's own variables (the VM's free space is 512 on the Thymio II).
    pub(crate) fn user_words(&self) -> usize {
        self.user_words
    }

    /// Run the initialisation (variable initialisers, then the top-level statements); its
    /// step count.
    pub(crate) fn run_init(&mut self) -> Res<usize> {
        self.steps = 0;
        let program = Rc::clone(&self.program);
        for d in &program.decls {
            if let Some(items) = &d.init {
                let (addr, _) = self.vars[&d.name];
                for (k, e) in items.iter().enumerate() {
                    self.mem[addr + k] = self.eval(e)?;
                    self.steps += 1;
                }
            }
        }
        self.block(&program.init)?;
        Ok(self.steps + 1)
    }

    /// Run the handler of event `name` (nothing if the program has none); its step count.
    pub(crate) fn run_event(&mut self, name: &str) -> Res<usize> {
        self.steps = 0;
        let program = Rc::clone(&self.program);
        let Some(body) = program.events.get(name) else {
            return Ok(0);
        };
        self.block(body)?;
        Ok(self.steps + 1)
    }

    /// The value of variable `name`.
    pub(crate) fn get(&self, name: &str) -> Option<&[i16]> {
        self.vars.get(name).map(|&(a, n)| &self.mem[a..a + n])
    }

    /// The events emitted so far (name, values), taken out.
    #[cfg(test)]
    pub(crate) fn take_emitted(&mut self) -> Vec<(String, Vec<i16>)> {
        std::mem::take(&mut self.emitted)
    }

    /// Set variable `name` (its first `values.len()` elements).
    pub(crate) fn set(&mut self, name: &str, values: &[i16]) -> Res<()> {
        let Some(&(a, n)) = self.vars.get(name) else {
            return stop(format!("no variable {name}"));
        };
        if values.len() > n {
            return stop(format!("{name} has {n} elements"));
        }
        self.mem[a..a + values.len()].copy_from_slice(values);
        Ok(())
    }

    fn tick(&mut self, n: usize) -> Res<()> {
        self.steps += n;
        if self.steps > STEP_CAP {
            return stop("step cap reached (runaway loop)");
        }
        Ok(())
    }

    fn addr(&self, name: &str, index: i64) -> Res<usize> {
        let Some(&(a, n)) = self.vars.get(name) else {
            return stop(format!("no variable {name}"));
        };
        if index < 0 || index as usize >= n {
            return stop(format!("{name}[{index}] out of bounds (size {n})"));
        }
        Ok(a + index as usize)
    }

    fn block(&mut self, stmts: &[Stmt]) -> Res<Flow> {
        for s in stmts {
            if self.stmt(s)? == Flow::Return {
                return Ok(Flow::Return);
            }
        }
        Ok(Flow::Next)
    }

    fn stmt(&mut self, s: &Stmt) -> Res<Flow> {
        match s {
            Stmt::Assign(name, index, e) => {
                let v = self.eval(e)?;
                let i = match index {
                    Some(ix) => self.eval(ix)?,
                    None => 0,
                };
                let a = self.addr(name, i64::from(i))?;
                self.mem[a] = v;
                self.tick(1)?;
            }
            Stmt::If(arms, otherwise) => {
                for (c, body) in arms {
                    if self.cond(c)? {
                        self.tick(1)?; // the jump past the other arms
                        return self.block(body);
                    }
                }
                return self.block(otherwise);
            }
            Stmt::While(c, body) => {
                while self.cond(c)? {
                    if self.block(body)? == Flow::Return {
                        return Ok(Flow::Return);
                    }
                    self.tick(1)?;
                }
            }
            Stmt::For(var, lo, hi, body) => return self.for_loop(var, lo, hi, body),
            Stmt::Call(f, args) => self.call(f, args)?,
            Stmt::CallSub(name) => {
                let program = Rc::clone(&self.program);
                let Some(body) = program.subs.get(name) else {
                    return stop(format!("no sub {name}"));
                };
                self.tick(2)?; // call and return
                self.block(body)?;
            }
            Stmt::Return => return Ok(Flow::Return),
            Stmt::Emit(event, var) => {
                let Some(values) = self.get(var).map(<[i16]>::to_vec) else {
                    return stop(format!("no variable {var}"));
                };
                self.emitted.push((event.clone(), values));
                self.tick(1)?;
            }
        }
        Ok(Flow::Next)
    }

    fn for_loop(&mut self, var: &str, lo: &Expr, hi: &Expr, body: &[Stmt]) -> Res<Flow> {
        let v = self.eval(lo)?;
        let a = self.addr(var, 0)?;
        self.mem[a] = v;
        self.tick(1)?;
        loop {
            let end = self.eval(hi)?;
            self.tick(2)?; // load the variable, conditional branch
            if self.mem[a] > end {
                return Ok(Flow::Next);
            }
            if self.block(body)? == Flow::Return {
                return Ok(Flow::Return);
            }
            self.mem[a] = self.mem[a].wrapping_add(1);
            self.tick(5)?; // load, immediate, add, store, jump back
        }
    }

    fn cond(&mut self, c: &Cond) -> Res<bool> {
        let v = self.cond_value(c)?;
        self.tick(1)?; // the conditional branch
        Ok(v)
    }

    fn cond_value(&mut self, c: &Cond) -> Res<bool> {
        Ok(match c {
            Cond::Cmp(op, a, b) => {
                let (a, b) = (self.eval(a)?, self.eval(b)?);
                match op {
                    Cmp::Eq => a == b,
                    Cmp::Ne => a != b,
                    Cmp::Lt => a < b,
                    Cmp::Le => a <= b,
                    Cmp::Gt => a > b,
                    Cmp::Ge => a >= b,
                }
            }
            Cond::And(a, b) | Cond::Or(a, b) => {
                let (x, y) = (self.cond_value(a)?, self.cond_value(b)?);
                self.tick(2)?; // both comparisons as values, then the logical operator
                if matches!(c, Cond::And(..)) {
                    x && y
                } else {
                    x || y
                }
            }
            Cond::Not(a) => !self.cond_value(a)?,
        })
    }

    fn eval(&mut self, e: &Expr) -> Res<i16> {
        if let Some(v) = fold(e) {
            self.tick(1)?;
            return Ok(v as i16);
        }
        self.tick(1)?;
        match e {
            Expr::Num(v) => Ok(*v as i16),
            Expr::Var(n) => Ok(self.mem[self.addr(n, 0)?]),
            Expr::Index(n, i) => {
                let i = self.eval(i)?;
                Ok(self.mem[self.addr(n, i64::from(i))?])
            }
            Expr::Neg(a) => Ok(self.eval(a)?.wrapping_neg()),
            Expr::Abs(a) => Ok(self.eval(a)?.wrapping_abs()),
            Expr::Bin(op, a, b) => {
                let x = self.eval(a)?;
                let pot = fold(b).and_then(power_of_two);
                let y = self.eval(b)?;
                binary(*op, x, y, pot)
            }
        }
    }
}

/// `x op y` in 16 bits as the VM computes it (`pot`: the right operand is a constant `2^k`,
/// which the compiler turns `/` into `>> k` for).
fn binary(op: Op, x: i16, y: i16, pot: Option<u32>) -> Res<i16> {
    let (a, b) = (i32::from(x), i32::from(y));
    let r = match op {
        Op::Div if pot.is_some() => a >> pot.unwrap_or(0),
        Op::Div | Op::Mod if b == 0 => return stop("division by zero"),
        Op::Div => a / b,
        Op::Mod => a % b,
        Op::Add => a + b,
        Op::Sub => a - b,
        Op::Mul => a * b,
        Op::Shl => a.wrapping_shl(b as u32),
        Op::Shr => a.wrapping_shr(b as u32),
        Op::And => a & b,
        Op::Or => a | b,
        Op::Xor => a ^ b,
    };
    Ok(r as i16)
}

impl Machine {
    /// The memory range of a native's argument; an expression is evaluated into a temporary
    /// appended after the variables (as the compiler allocates temporaries).
    fn arg_range(&mut self, arg: &Arg) -> Res<(usize, usize)> {
        match arg {
            Arg::Mem(name, None) => {
                self.tick(1)?;
                self.vars
                    .get(name)
                    .copied()
                    .map_or_else(|| stop(format!("no variable {name}")), Ok)
            }
            Arg::Mem(name, Some((lo, hi))) => {
                let (Some(lo), Some(hi)) = (fold(lo), fold(hi)) else {
                    return stop("native arguments with a run-time index are not supported");
                };
                self.tick(1)?;
                let a = self.addr(name, lo)?;
                self.addr(name, hi)?;
                Ok((a, (hi - lo + 1) as usize))
            }
            Arg::Value(e) => {
                let v = self.eval(e)?;
                self.tick(2)?; // store into the temporary, push its address
                self.mem.push(v);
                Ok((self.mem.len() - 1, 1))
            }
        }
    }

    fn call(&mut self, f: &str, args: &[Arg]) -> Res<()> {
        let base = self.mem.len();
        let ranges: Res<Vec<(usize, usize)>> = args.iter().map(|a| self.arg_range(a)).collect();
        let result = ranges.and_then(|ranges| {
            self.tick(2)?; // the template size pushed, the native call
            native(&mut self.mem, f, &ranges)
        });
        self.mem.truncate(base);
        result
    }
}

/// Run native `f` on `args` (address, size) in `mem`.
fn native(mem: &mut [i16], f: &str, args: &[(usize, usize)]) -> Res<()> {
    let arity = match f {
        "math.copy" | "math.fill" => 2,
        "math.mul" | "math.min" | "math.max" => 3,
        "math.clamp" | "math.muldiv" | "math.dot" => 4,
        _ => return stop(format!("native {f} is not supported")),
    };
    if args.len() != arity {
        return stop(format!("{f} takes {arity} arguments"));
    }
    let len = args[usize::from(f == "math.dot")].1;
    let sized = |k: usize| (f == "math.fill" && k == 1) || (f == "math.dot" && (k == 0 || k == 3));
    if args
        .iter()
        .enumerate()
        .any(|(k, a)| !sized(k) && a.1 != len)
    {
        return stop(format!("{f}: arguments of different sizes"));
    }
    let at = |k: usize, i: usize| args[k].0 + i;
    if f == "math.dot" {
        let shift = mem[args[3].0];
        let mut acc: i32 = 0;
        for i in 0..len {
            acc = acc.wrapping_add(i32::from(mem[at(1, i)]) * i32::from(mem[at(2, i)]));
        }
        mem[args[0].0] = if shift > 32 {
            0
        } else {
            acc.wrapping_shr(shift as u32) as i16
        };
        return Ok(());
    }
    for i in 0..len {
        let v = |k: usize| i32::from(mem[at(k, i)]);
        mem[at(0, i)] = match f {
            "math.copy" => v(1) as i16,
            "math.fill" => mem[args[1].0],
            "math.mul" => (v(1) * v(2)) as i16,
            "math.min" => v(1).min(v(2)) as i16,
            "math.max" => v(1).max(v(2)) as i16,
            "math.clamp" => {
                (if v(1) > v(3) {
                    v(3)
                } else if v(1) < v(2) {
                    v(2)
                } else {
                    v(1)
                }) as i16
            }
            _ => {
                if v(3) == 0 {
                    return stop("math.muldiv: division by zero");
                }
                ((i64::from(v(1)) * i64::from(v(2))) / i64::from(v(3))) as i16
            }
        };
    }
    Ok(())
}

/// Estimated bytecode words of the program (the VM holds 1534 on the Thymio II): per
/// instruction the compiler emits, one word, two for a large immediate (outside ±2048), an
/// indirect load or store and a conditional branch; plus the event vector table.
pub(crate) fn bytecode_words(code: &str, consts: &[(String, i64)]) -> Res<usize> {
    let consts_map: HashMap<String, i64> = consts.iter().cloned().collect();
    let toks = lex(code)?;
    let p = Parser {
        toks: &toks,
        at: 0,
        consts: &consts_map,
    }
    .program()?;
    let mut words = 1 + 2 * p.events.len();
    for d in &p.decls {
        for e in d.init.iter().flatten() {
            words += expr_words(e) + 1;
        }
    }
    for body in std::iter::once(&p.init)
        .chain(p.subs.values())
        .chain(p.events.values())
    {
        words += block_words(body) + 1;
    }
    Ok(words)
}

fn expr_words(e: &Expr) -> usize {
    if let Some(v) = fold(e) {
        return 1 + usize::from(large(v));
    }
    match e {
        Expr::Num(_) | Expr::Var(_) => 1,
        Expr::Index(_, i) => expr_words(i) + 2,
        Expr::Neg(a) | Expr::Abs(a) => expr_words(a) + 1,
        Expr::Bin(_, a, b) => expr_words(a) + expr_words(b) + 1,
    }
}

fn cond_words(c: &Cond) -> usize {
    match c {
        Cond::Cmp(_, a, b) => expr_words(a) + expr_words(b),
        Cond::And(a, b) | Cond::Or(a, b) => cond_words(a) + cond_words(b) + 3,
        Cond::Not(a) => cond_words(a) + 1,
    }
}

fn block_words(body: &[Stmt]) -> usize {
    body.iter()
        .map(|s| match s {
            Stmt::Assign(_, None, e) => expr_words(e) + 1,
            Stmt::Assign(_, Some(i), e) => expr_words(e) + expr_words(i) + 2,
            Stmt::If(arms, otherwise) => {
                let arms: usize = arms
                    .iter()
                    .map(|(c, b)| cond_words(c) + 3 + block_words(b))
                    .sum();
                arms + block_words(otherwise)
            }
            Stmt::While(c, b) => cond_words(c) + 3 + block_words(b),
            Stmt::For(_, lo, hi, b) => expr_words(lo) + expr_words(hi) + 9 + block_words(b),
            Stmt::Call(_, args) => {
                let pushes: usize = args
                    .iter()
                    .map(|a| match a {
                        Arg::Mem(..) => 1,
                        Arg::Value(e) => expr_words(e) + 2,
                    })
                    .sum();
                pushes + 2
            }
            Stmt::CallSub(_) | Stmt::Return => 1,
            Stmt::Emit(..) => 3,
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(code: &str) -> Machine {
        let mut m = Machine::load(code, &[("K".into(), 1000)], &[("t", 2)]).unwrap();
        m.run_init().unwrap();
        m
    }

    #[test]
    fn arithmetic_wraps_at_16_bits_and_divides_as_c() {
        let m = run(
            "var m = -7\nvar a = 30000\nvar two = 2\nvar b\nvar c\nvar d\nvar e\nvar f\nb = a + a\nc = -7 / a * 0 + m / 2\nd = m / 3\ne = m % 3\nf = m / two\nt[0] = (0 - 7) / 2",
        );
        assert_eq!(m.get("b"), Some(&[-5536i16][..]));
        // m / 2 is rewritten to a shift: −4, not C's −3 (a divisor in a variable is not: −3);
        // / 3 truncates: −2, % keeps the sign. (The playground's VM agrees: see playground.rs.)
        assert_eq!(m.get("c"), Some(&[-4i16][..]));
        assert_eq!(m.get("f"), Some(&[-3i16][..]));
        assert_eq!(m.get("d"), Some(&[-2i16][..]));
        assert_eq!(m.get("e"), Some(&[-1i16][..]));
        // A constant expression is folded in C: (0 - 7) / 2 = −3.
        assert_eq!(m.get("t").unwrap()[0], -3);
    }

    #[test]
    fn constant_expressions_fold_without_wrapping() {
        // 1000 * 100 / 50 = 2000 folded in C int; at run time 1000 * 100 would wrap.
        let m = run("var a\nvar k = 1000\na = K * 100 / 50\nt[0] = k * 100 / 50");
        assert_eq!(m.get("a"), Some(&[2000i16][..]));
        assert_eq!(
            m.get("t").unwrap()[0],
            ((100_000i32 as i16) as i32 / 50) as i16
        );
    }

    #[test]
    fn natives_use_32_bit_intermediates() {
        let m = run(
            "var a[2] = [30000, 30000]\nvar b[2] = [2, 2]\nvar r\nvar q\nvar s = 4\ncall math.dot(r, a, b, s)\ncall math.muldiv(q, 30000, 4, 8)",
        );
        // 120000 >> 4 = 7500 (a 16-bit sum would have wrapped to −11072 >> 4 = −692).
        assert_eq!(m.get("r"), Some(&[7500i16][..]));
        assert_eq!(m.get("q"), Some(&[15000i16][..]));
    }

    #[test]
    fn loops_subs_and_conditions_run_with_step_counts() {
        let mut m = run(
            "var i\nvar s = 0\nsub add\ns = s + i\nonevent go\nfor i in 0:3 do\ncallsub add\nend\nif s > 5 and not s == 7 then\nt[1] = 1\nelseif s == 6 then\nt[1] = 2\nelse\nt[1] = 3\nend",
        );
        let steps = m.run_event("go").unwrap();
        assert_eq!(m.get("s"), Some(&[6i16][..]));
        assert_eq!(m.get("t"), Some(&[0i16, 1][..]));
        assert!(steps > 40 && steps < 120, "{steps}");
        assert_eq!(m.run_event("nothing").unwrap(), 0);
    }

    #[test]
    fn the_vm_stops_on_bad_indices_and_zero_divisors() {
        let mut m = Machine::load(
            "var a[2]\nvar i = 2\nvar z = 0\nonevent x\na[i] = 1\nonevent y\na[0] = 1 / z",
            &[],
            &[],
        )
        .unwrap();
        m.run_init().unwrap();
        assert!(matches!(m.run_event("x"), Err(AsebaError::Stopped(_))));
        assert!(matches!(m.run_event("y"), Err(AsebaError::Stopped(_))));
    }

    #[test]
    fn unknown_syntax_is_a_parse_error() {
        assert!(matches!(
            Machine::load("var a\na = = 1", &[], &[]),
            Err(AsebaError::Parse { .. })
        ));
        assert!(matches!(
            Machine::load("var a\na = 1 @ 2", &[], &[]),
            Err(AsebaError::Parse { .. })
        ));
    }
}
