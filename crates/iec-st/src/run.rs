//! The interpreter: runs resolved statements over an instance's memory.

use crate::code::{
    Arith, BlockCall, Builtin, Compare, ElemRef, Expr, FunctionCall, Logic, Place, Stmt,
};
use crate::error::{Fault, RuntimeError};
use crate::program::Pou;
use crate::types::IntType;

/// Faults are rare; boxing keeps the hot `Result`s two words wide.
pub(crate) type Run<T> = Result<T, Box<RuntimeError>>;

fn fault<T>(fault: Fault, line: u32) -> Run<T> {
    Err(Box::new(RuntimeError { fault, line }))
}

/// How a statement list ended.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Flow {
    Next,
    Exit,
    Return,
}

/// One call's execution state.
pub(crate) struct Machine<'a> {
    pub pous: &'a [Pou],
    pub mem: &'a mut [i64],
    /// Function arguments, evaluated before the function's frame is reset.
    pub stack: &'a mut Vec<i64>,
    pub iterations: u64,
    pub iteration_limit: u64,
}

/// Evaluates an expression without variables (constant folding).
pub(crate) fn eval_const(expr: &Expr) -> Run<i64> {
    let mut stack = Vec::new();
    Machine {
        pous: &[],
        mem: &mut [],
        stack: &mut stack,
        iterations: 0,
        iteration_limit: 0,
    }
    .eval(expr, 0)
}

impl Machine<'_> {
    /// Runs POU `pou`'s body on the frame at `base`.
    pub fn run_pou(&mut self, pou: usize, base: usize) -> Run<()> {
        let pous = self.pous;
        let pou = &pous[pou];
        for &(slot, cell) in &pou.temps {
            self.mem[base + slot as usize] = cell;
        }
        self.block(&pou.body, base)?;
        Ok(())
    }

    fn tick(&mut self, line: u32) -> Run<()> {
        self.iterations += 1;
        if self.iterations > self.iteration_limit {
            return fault(Fault::IterationLimit(self.iteration_limit), line);
        }
        Ok(())
    }

    fn block(&mut self, stmts: &[Stmt], base: usize) -> Run<Flow> {
        for stmt in stmts {
            let flow = self.stmt(stmt, base)?;
            if flow != Flow::Next {
                return Ok(flow);
            }
        }
        Ok(Flow::Next)
    }

    fn stmt(&mut self, stmt: &Stmt, base: usize) -> Run<Flow> {
        match stmt {
            Stmt::Assign(place, value) => {
                let v = self.eval(value, base)?;
                self.store(place, base, v)?;
            }
            Stmt::If {
                branches,
                otherwise,
            } => {
                for (cond, body) in branches {
                    if self.eval(cond, base)? != 0 {
                        return self.block(body, base);
                    }
                }
                return self.block(otherwise, base);
            }
            Stmt::Case {
                selector,
                unsigned,
                labels,
                arms,
                otherwise,
            } => {
                let cell = self.eval(selector, base)?;
                let value = if *unsigned {
                    i128::from(cell as u64)
                } else {
                    i128::from(cell)
                };
                let after = labels.partition_point(|&(lo, _, _)| lo <= value);
                return match after.checked_sub(1).map(|i| labels[i]) {
                    Some((_, hi, arm)) if value <= hi => self.block(&arms[arm as usize], base),
                    _ => self.block(otherwise, base),
                };
            }
            Stmt::For {
                var,
                ty,
                from,
                to,
                by,
                body,
                line,
            } => return self.for_loop(*var, *ty, [from, to, by], body, *line, base),
            Stmt::While { cond, body, line } => {
                while self.eval(cond, base)? != 0 {
                    self.tick(*line)?;
                    match self.block(body, base)? {
                        Flow::Next => {}
                        Flow::Exit => break,
                        Flow::Return => return Ok(Flow::Return),
                    }
                }
            }
            Stmt::Repeat { body, until, line } => loop {
                self.tick(*line)?;
                match self.block(body, base)? {
                    Flow::Next => {}
                    Flow::Exit => break,
                    Flow::Return => return Ok(Flow::Return),
                }
                if self.eval(until, base)? != 0 {
                    break;
                }
            },
            Stmt::Exit => return Ok(Flow::Exit),
            Stmt::Return => return Ok(Flow::Return),
            Stmt::CallBlock(call) => self.call_block(call, base)?,
            Stmt::CallFunction(call) => {
                self.call_function(call, base)?;
            }
        }
        Ok(Flow::Next)
    }

    /// IEC FOR: bounds and step evaluated once; the loop ends when the
    /// variable passes the final value (in the step's direction).
    fn for_loop(
        &mut self,
        var: u32,
        ty: IntType,
        [from, to, by]: [&Expr; 3],
        body: &[Stmt],
        line: u32,
        base: usize,
    ) -> Run<Flow> {
        let start = self.eval(from, base)?;
        let end = self.eval(to, base)?;
        let step = self.eval(by, base)?;
        let slot = base + var as usize;
        let unsigned = !ty.is_signed();
        let upward = unsigned || step >= 0;
        self.mem[slot] = start;
        loop {
            let i = self.mem[slot];
            let past = match (unsigned, upward) {
                (true, _) => (i as u64) > (end as u64),
                (false, true) => i > end,
                (false, false) => i < end,
            };
            if past {
                return Ok(Flow::Next);
            }
            self.tick(line)?;
            match self.block(body, base)? {
                Flow::Next => {}
                Flow::Exit => return Ok(Flow::Next),
                Flow::Return => return Ok(Flow::Return),
            }
            self.mem[slot] = ty.normalize(i.wrapping_add(step));
        }
    }

    fn call_block(&mut self, call: &BlockCall, base: usize) -> Run<()> {
        let frame = base + call.instance as usize;
        for (slot, arg) in &call.inputs {
            let v = self.eval(arg, base)?;
            self.mem[frame + *slot as usize] = v;
        }
        self.run_pou(call.pou as usize, frame)?;
        for (slot, place) in &call.outputs {
            let v = self.mem[frame + *slot as usize];
            self.store(place, base, v)?;
        }
        Ok(())
    }

    fn call_function(&mut self, call: &FunctionCall, base: usize) -> Run<i64> {
        let mark = self.stack.len();
        for (_, arg) in &call.args {
            let v = self.eval(arg, base)?;
            self.stack.push(v);
        }
        let pous = self.pous;
        let pou = &pous[call.pou as usize];
        let frame = pou.base;
        self.mem[frame..frame + pou.size].copy_from_slice(&pou.init);
        for (k, (slot, _)) in call.args.iter().enumerate() {
            self.mem[frame + *slot as usize] = self.stack[mark + k];
        }
        self.stack.truncate(mark);
        self.block(&pou.body, frame)?;
        let (result, _) = pou.result.expect("a function has a result");
        Ok(self.mem[frame + result as usize])
    }

    fn store(&mut self, place: &Place, base: usize, v: i64) -> Run<()> {
        let at = match place {
            Place::Slot(slot) => base + *slot as usize,
            Place::Elem(elem) => self.elem_at(elem, base)?,
        };
        self.mem[at] = v;
        Ok(())
    }

    fn elem_at(&mut self, elem: &ElemRef, base: usize) -> Run<usize> {
        let mut offset = 0usize;
        for dim in elem.dims.iter() {
            let cell = self.eval(&dim.index, base)?;
            let index = if dim.unsigned {
                i128::from(cell as u64)
            } else {
                i128::from(cell)
            };
            if index < i128::from(dim.lo) || index > i128::from(dim.hi) {
                return fault(
                    Fault::IndexOutOfRange {
                        index,
                        lo: dim.lo,
                        hi: dim.hi,
                    },
                    elem.line,
                );
            }
            offset += (index - i128::from(dim.lo)) as usize * dim.stride as usize;
        }
        Ok(base + elem.base as usize + offset)
    }

    pub(crate) fn eval(&mut self, expr: &Expr, base: usize) -> Run<i64> {
        Ok(match expr {
            Expr::Const(v) => *v,
            Expr::Load(slot) => self.mem[base + *slot as usize],
            Expr::LoadElem(elem) => {
                let at = self.elem_at(elem, base)?;
                self.mem[at]
            }
            Expr::Not(e) => self.eval(e, base)? ^ 1,
            Expr::BitNot(ty, e) => ty.normalize(!self.eval(e, base)?),
            Expr::Neg(ty, e) => ty.normalize(self.eval(e, base)?.wrapping_neg()),
            Expr::Arith(op, ty, operands) => {
                let a = self.eval(&operands.0, base)?;
                let b = self.eval(&operands.1, base)?;
                ty.normalize(match op {
                    Arith::Add => a.wrapping_add(b),
                    Arith::Sub => a.wrapping_sub(b),
                    Arith::Mul => a.wrapping_mul(b),
                })
            }
            Expr::Divide {
                modulo,
                ty,
                operands,
                line,
            } => {
                let a = self.eval(&operands.0, base)?;
                let b = self.eval(&operands.1, base)?;
                if b == 0 {
                    return fault(Fault::DivisionByZero, *line);
                }
                match (ty.is_signed(), modulo) {
                    (true, false) => ty.normalize(a.wrapping_div(b)),
                    (true, true) => a.wrapping_rem(b),
                    (false, false) => ((a as u64) / (b as u64)) as i64,
                    (false, true) => ((a as u64) % (b as u64)) as i64,
                }
            }
            Expr::Compare {
                op,
                unsigned,
                operands,
            } => {
                let a = self.eval(&operands.0, base)?;
                let b = self.eval(&operands.1, base)?;
                let ordering = if *unsigned {
                    (a as u64).cmp(&(b as u64))
                } else {
                    a.cmp(&b)
                };
                i64::from(match op {
                    Compare::Eq => ordering.is_eq(),
                    Compare::Ne => ordering.is_ne(),
                    Compare::Lt => ordering.is_lt(),
                    Compare::Gt => ordering.is_gt(),
                    Compare::Le => ordering.is_le(),
                    Compare::Ge => ordering.is_ge(),
                })
            }
            Expr::Logic(op, operands) => {
                let a = self.eval(&operands.0, base)?;
                let b = self.eval(&operands.1, base)?;
                match op {
                    Logic::And => a & b,
                    Logic::Or => a | b,
                    Logic::Xor => a ^ b,
                }
            }
            Expr::Truncate(ty, e) => ty.normalize(self.eval(e, base)?),
            Expr::NonZero(e) => i64::from(self.eval(e, base)? != 0),
            Expr::Builtin(f, args) => self.builtin(*f, args, base)?,
            Expr::Call(call) => self.call_function(call, base)?,
        })
    }

    fn builtin(&mut self, f: Builtin, args: &[Expr], base: usize) -> Run<i64> {
        let less = |unsigned: bool, a: i64, b: i64| {
            if unsigned {
                (a as u64) < (b as u64)
            } else {
                a < b
            }
        };
        let first = self.eval(&args[0], base)?;
        Ok(match f {
            Builtin::Abs(ty) => ty.normalize(first.wrapping_abs()),
            Builtin::Min { unsigned } | Builtin::Max { unsigned } => {
                let want_min = matches!(f, Builtin::Min { .. });
                let mut best = first;
                for arg in &args[1..] {
                    let v = self.eval(arg, base)?;
                    if less(unsigned, v, best) == want_min && v != best {
                        best = v;
                    }
                }
                best
            }
            Builtin::Limit { unsigned } => {
                let input = self.eval(&args[1], base)?;
                let high = self.eval(&args[2], base)?;
                let raised = if less(unsigned, input, first) {
                    first
                } else {
                    input
                };
                if less(unsigned, high, raised) {
                    high
                } else {
                    raised
                }
            }
            Builtin::Sel => {
                let in0 = self.eval(&args[1], base)?;
                let in1 = self.eval(&args[2], base)?;
                if first != 0 {
                    in1
                } else {
                    in0
                }
            }
            Builtin::Shl(ty) | Builtin::Shr(ty) | Builtin::Rol(ty) | Builtin::Ror(ty) => {
                let n = self.eval(&args[1], base)? as u64;
                shift(f, ty, first as u64, n) as i64
            }
        })
    }
}

/// SHL/SHR shift in zeros (a count of the width or more gives 0); ROL/ROR
/// rotate within the width. `value` is a zero-extended bit string.
fn shift(f: Builtin, ty: IntType, value: u64, n: u64) -> u64 {
    let bits = u64::from(ty.bits());
    let mask = if bits == 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    };
    match f {
        Builtin::Shl(_) if n >= bits => 0,
        Builtin::Shr(_) if n >= bits => 0,
        Builtin::Shl(_) => (value << n) & mask,
        Builtin::Shr(_) => value >> n,
        Builtin::Rol(_) | Builtin::Ror(_) => {
            let n = n % bits;
            if n == 0 {
                return value;
            }
            let left = if matches!(f, Builtin::Rol(_)) {
                n
            } else {
                bits - n
            };
            ((value << left) | (value >> (bits - left))) & mask
        }
        _ => unreachable!("only shifts and rotations"),
    }
}
