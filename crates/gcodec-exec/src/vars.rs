//! The variable store of a channel: R parameters, `DEF` variables per
//! program level and global user data (GUD).
//!
//! * **R parameters**: REAL, `R0 … R(n−1)`. The profile has no key for
//!   their number (MD28050 `$MC_MM_NUM_R_PARAM`), so a store made for a
//!   profile has [`DEFAULT_R_PARAMETERS`] (100, the common 840D sl
//!   setting; reference §7.2).
//! * **Local variables** (`DEF` in a program, LUD): one table per program
//!   level. [`Variables::push_level`] starts a level when a subprogram is
//!   called, [`Variables::pop_level`] drops it and its variables when the
//!   subprogram returns. A name is looked up in the current level, then
//!   (only with [`Variables::set_lud_extended_scope`], MD11120) in the main
//!   program's level, then in the global data.
//! * **Global user data** (GUD of the definition files): one table shared
//!   by every level, declared with [`Scope::Global`].
//!
//! Every variable is an array of its elements in storage order (the last
//! index runs fastest); a single value is an array of one element. A
//! `STRING` element indexed once more is one of its characters (a CHAR).
//! Lookups hash the name in place (no allocation); the tables of dropped
//! levels are kept for reuse, and assignments overwrite in place, so that
//! the store does not grow with the number of assignments or calls.
//!
//! The store draws on the run's budgets ([`crate::budget`]): a declaration
//! takes its bytes from the memory for variables before it allocates
//! them (a replaced variable and a dropped level give theirs back), and
//! the elements declarations initialise and lists and fills write count
//! as work.

use std::sync::Arc;

use gcodec_ail::VarKind;
use gcodec_lang::DataType;
use gcodec_profile::DEFAULT_MAX_VARIABLE_MEMORY;
use gcodec_source::{codes, cp1252};

use crate::budget::{DEFAULT_MAX_WORK, MemoryBudget, WorkBudget, element_bytes};
use crate::value::{RtValue, RunError, char_code};

/// The number of R parameters when nothing says otherwise (MD28050).
pub const DEFAULT_R_PARAMETERS: usize = 100;

/// At most this many dimensions (reference §7.1: newer manuals allow 3).
pub const MAX_DIMENSIONS: usize = 3;

/// At most this many elements in one variable: a guard against a
/// computed dimension exhausting memory (the control's memory for user
/// data is far smaller).
pub const MAX_ELEMENTS: usize = 1 << 20;

/// Where a declaration puts its variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// The current program level (LUD/PUD).
    Local,
    /// Global user data, seen from every level (GUD).
    Global,
}

/// A global variable of the definition files (GUD), as the channel
/// declares it before a run ([`crate::channel::Channel::with_globals`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Global {
    /// Upper case.
    pub name: String,
    pub data_type: DataType,
    /// The array dimensions; empty for a single value.
    pub dims: Vec<usize>,
    /// Where it is defined: the definition file, 1-based line and byte
    /// column.
    pub file: Arc<str>,
    pub line: u32,
    pub col: u32,
}

/// One declared variable.
#[derive(Clone, Debug)]
pub struct Variable {
    ty: DataType,
    dims: [usize; MAX_DIMENSIONS],
    rank: u8,
    data: Vec<RtValue>,
}

impl Variable {
    /// The number of elements of an array of `dims`, if gcodec can hold
    /// it.
    fn element_count(dims: &[usize]) -> Result<usize, RunError> {
        if dims.len() > MAX_DIMENSIONS {
            return Err(RunError::new(
                codes::run::INVALID_DECLARATION,
                format!(
                    "{} dimensions: at most {MAX_DIMENSIONS} are allowed",
                    dims.len()
                ),
            ));
        }
        let mut total = 1usize;
        for &n in dims {
            if n == 0 {
                return Err(RunError::new(
                    codes::run::INVALID_DECLARATION,
                    "an array dimension must be at least 1",
                ));
            }
            total = total.saturating_mul(n);
        }
        if total > MAX_ELEMENTS {
            return Err(RunError::new(
                codes::run::INVALID_DECLARATION,
                format!("an array of {total} elements is larger than {MAX_ELEMENTS}"),
            ));
        }
        Ok(total)
    }

    /// A variable of `total` elements ([`Variable::element_count`] of
    /// `dims`), each its type's initial value.
    fn new(ty: DataType, dims: &[usize], total: usize) -> Self {
        let mut d = [0; MAX_DIMENSIONS];
        for (slot, &n) in d.iter_mut().zip(dims) {
            *slot = n;
        }
        Self {
            ty,
            dims: d,
            rank: dims.len() as u8,
            data: vec![RtValue::initial(ty); total],
        }
    }

    /// The bytes it counts against the memory for variables.
    fn bytes(&self) -> u64 {
        self.data.len() as u64 * element_bytes(self.ty)
    }

    /// The dimensions (empty for a single value).
    pub fn dims(&self) -> &[usize] {
        &self.dims[..usize::from(self.rank)]
    }

    /// The elements in storage order.
    pub fn elements(&self) -> &[RtValue] {
        &self.data
    }

    /// The storage position of the element `indices` name (exactly one
    /// index per dimension).
    fn offset(&self, name: &str, indices: &[i32]) -> Result<usize, RunError> {
        let mut offset = 0usize;
        for (i, (&index, &dim)) in indices.iter().zip(self.dims()).enumerate() {
            let ok = usize::try_from(index).ok().filter(|&x| x < dim);
            let Some(index) = ok else {
                return Err(RunError::new(
                    codes::run::INDEX_OUT_OF_RANGE,
                    format!(
                        "index {index} of `{name}` is outside 0…{} (dimension {})",
                        dim - 1,
                        i + 1
                    ),
                ));
            };
            offset = offset * dim + index;
        }
        Ok(offset)
    }

    fn index_count(&self, name: &str, given: usize) -> RunError {
        let extra = if matches!(self.ty, DataType::String { .. }) {
            " (one more for a character of a STRING)"
        } else {
            ""
        };
        RunError::new(
            codes::run::INDEX_COUNT,
            format!("`{name}` takes {} indices{extra}, not {given}", self.rank),
        )
    }

    /// The element (or a STRING's character) `indices` name; `name` is
    /// for messages.
    pub fn read(&self, name: &str, indices: &[i32]) -> Result<RtValue, RunError> {
        let rank = usize::from(self.rank);
        if indices.len() == rank {
            let offset = self.offset(name, indices)?;
            return Ok(self.data[offset].clone());
        }
        if indices.len() == rank + 1
            && let DataType::String { .. } = self.ty
        {
            let offset = self.offset(name, &indices[..rank])?;
            let RtValue::String(s) = &self.data[offset] else {
                return Err(self.index_count(name, indices.len()));
            };
            let at = indices[rank];
            return match usize::try_from(at).ok().and_then(|i| s.chars().nth(i)) {
                Some(c) => char_code(c).map(RtValue::Char),
                None => Err(outside_string(name, at, s)),
            };
        }
        Err(self.index_count(name, indices.len()))
    }

    /// Writes the element (or a STRING's character) `indices` name,
    /// converting `value` to the variable's type.
    pub fn write(&mut self, name: &str, indices: &[i32], value: &RtValue) -> Result<(), RunError> {
        let rank = usize::from(self.rank);
        if indices.len() == rank {
            let offset = self.offset(name, indices)?;
            self.data[offset] = value.convert_to(self.ty)?;
            return Ok(());
        }
        if indices.len() == rank + 1
            && let DataType::String { .. } = self.ty
        {
            let c = value.to_char()?;
            let offset = self.offset(name, &indices[..rank])?;
            let RtValue::String(s) = &self.data[offset] else {
                return Err(self.index_count(name, indices.len()));
            };
            let at = indices[rank];
            let Some(i) = usize::try_from(at).ok().filter(|&i| i < s.chars().count()) else {
                return Err(outside_string(name, at, s));
            };
            let text: String = s
                .chars()
                .enumerate()
                .map(|(k, x)| if k == i { cp1252(c) } else { x })
                .collect();
            self.data[offset] = RtValue::String(Arc::from(text.as_str()));
            return Ok(());
        }
        Err(self.index_count(name, indices.len()))
    }

    /// The storage position of the first element of a list assignment:
    /// all indices given, or none (the first element).
    fn start(&self, name: &str, indices: &[i32]) -> Result<usize, RunError> {
        if indices.is_empty() {
            return Ok(0);
        }
        if indices.len() != usize::from(self.rank) {
            return Err(self.index_count(name, indices.len()));
        }
        self.offset(name, indices)
    }

    /// Values for consecutive elements from storage position `first`;
    /// `None` keeps its element. All or nothing.
    fn put_list(
        &mut self,
        name: &str,
        first: usize,
        values: &[Option<RtValue>],
    ) -> Result<(), RunError> {
        check_span(name, first, values.len(), self.data.len())?;
        let mut converted = Vec::with_capacity(values.len());
        for v in values {
            converted.push(v.as_ref().map(|v| v.convert_to(self.ty)).transpose()?);
        }
        for (slot, v) in self.data[first..].iter_mut().zip(converted) {
            if let Some(v) = v {
                *slot = v;
            }
        }
        Ok(())
    }

    /// `value` for `count` elements from storage position `first` (to the
    /// end without `count`).
    fn put_fill(
        &mut self,
        name: &str,
        first: usize,
        value: &RtValue,
        count: Option<usize>,
    ) -> Result<(), RunError> {
        let count = count.unwrap_or(self.data.len().saturating_sub(first));
        check_span(name, first, count, self.data.len())?;
        let v = value.convert_to(self.ty)?;
        self.data[first..first + count].fill(v);
        Ok(())
    }
}

/// The initial values of a declaration.
#[derive(Clone, Copy, Debug)]
pub enum Init<'a> {
    /// The type's initial value everywhere.
    None,
    /// One value per element from the first on, in storage order; `None`
    /// keeps the type's initial value (`SET(1,,3)`). A single value for a
    /// single variable is a list of one.
    List(&'a [Option<RtValue>]),
    /// `REP(value, count)`: `value` for `count` elements from the first
    /// on (all without `count`).
    Repeat(&'a RtValue, Option<usize>),
}

/// Names are short and not chosen by an attacker, and lookups are on
/// the hot path of every loop: FxHash.
type FxMap<V> = rustc_hash::FxHashMap<Box<str>, V>;

/// The variables of one program level, or the global ones.
#[derive(Clone, Debug, Default)]
struct Table {
    index: FxMap<usize>,
    vars: Vec<Variable>,
}

impl Table {
    fn get(&self, name: &str) -> Option<&Variable> {
        self.index.get(name).map(|&i| &self.vars[i])
    }

    fn get_mut(&mut self, name: &str) -> Option<&mut Variable> {
        self.index.get(name).map(|&i| &mut self.vars[i])
    }

    fn declare(&mut self, name: &str, var: Variable) {
        if let Some(&i) = self.index.get(name) {
            // Declared again (a jump back over the DEF): a fresh variable
            // in the same place.
            self.vars[i] = var;
        } else {
            self.index.insert(Box::from(name), self.vars.len());
            self.vars.push(var);
        }
    }

    /// Drops every variable; returns the bytes they counted.
    fn clear(&mut self) -> u64 {
        let bytes = self.vars.iter().map(Variable::bytes).sum();
        self.index.clear();
        self.vars.clear();
        bytes
    }
}

/// The variables of a channel.
#[derive(Clone, Debug)]
pub struct Variables {
    r: Vec<f64>,
    globals: Table,
    /// Program levels; `levels[..depth]` are active, the rest are kept
    /// for reuse.
    levels: Vec<Table>,
    depth: usize,
    lud_extended_scope: bool,
    work: WorkBudget,
    memory: MemoryBudget,
}

impl Default for Variables {
    fn default() -> Self {
        Self::new(DEFAULT_R_PARAMETERS)
    }
}

impl Variables {
    /// A store with `r_parameters` R parameters, all 0, and the main
    /// program's level.
    pub fn new(r_parameters: usize) -> Self {
        Self {
            r: vec![0.0; r_parameters],
            globals: Table::default(),
            levels: vec![Table::default()],
            depth: 1,
            lud_extended_scope: false,
            work: WorkBudget::new(DEFAULT_MAX_WORK),
            memory: MemoryBudget::new(DEFAULT_MAX_VARIABLE_MEMORY),
        }
    }

    /// The budgets the store draws on: `max_work` element operations
    /// (`--max-work`) and `max_memory` bytes of variables alive at once
    /// (the profile's `[program] max_variable_memory`).
    pub fn with_budgets(mut self, max_work: u64, max_memory: u64) -> Self {
        self.work = WorkBudget::new(max_work);
        self.memory = MemoryBudget::new(max_memory);
        self
    }

    /// The element operations done so far ([`crate::budget::WorkBudget`]).
    pub fn work_done(&self) -> u64 {
        self.work.done()
    }

    /// The bytes the variables alive hold.
    pub fn memory_used(&self) -> u64 {
        self.memory.used()
    }

    /// MD11120 `$MN_LUD_EXTENDED_SCOPE`: the main program's variables are
    /// seen from its subprograms (PUD). Off by default.
    pub fn set_lud_extended_scope(&mut self, on: bool) {
        self.lud_extended_scope = on;
    }

    /// The number of R parameters.
    pub fn r_count(&self) -> usize {
        self.r.len()
    }

    /// The current program level: 1 for the main program.
    pub fn level(&self) -> usize {
        self.depth
    }

    /// A subprogram is called: a new level without variables.
    pub fn push_level(&mut self) {
        if self.depth == self.levels.len() {
            self.levels.push(Table::default());
        }
        self.depth += 1;
    }

    /// The subprogram returns: its variables are gone. The main program's
    /// level is never dropped (`false` then).
    pub fn pop_level(&mut self) -> bool {
        if self.depth <= 1 {
            return false;
        }
        self.depth -= 1;
        let freed = self.levels[self.depth].clear();
        self.memory.release(freed);
        true
    }

    /// Runs `f` with the level below the current one as the current level
    /// (a subprogram's caller): `VAR` parameters are read from and written
    /// back to it. In the main program's level, that level itself.
    pub fn with_caller_level<R>(&mut self, f: impl FnOnce(&mut Self) -> R) -> R {
        let depth = self.depth;
        self.depth = (depth - 1).max(1);
        let result = f(self);
        self.depth = depth;
        result
    }

    /// Declares `name` (upper case, as AIL writes it) with its initial
    /// values. A second declaration of a name in the same table replaces
    /// the variable. Its bytes are taken from the memory for variables
    /// and its elements counted as work before anything is allocated.
    pub fn declare(
        &mut self,
        scope: Scope,
        name: &str,
        ty: DataType,
        dims: &[usize],
        init: Init<'_>,
    ) -> Result<(), RunError> {
        let total = Variable::element_count(dims)?;
        let initialised = match init {
            Init::None => 0,
            Init::List(values) => values.len(),
            Init::Repeat(_, count) => count.unwrap_or(total),
        };
        self.work.spend(total.saturating_add(initialised))?;
        let bytes = total as u64 * element_bytes(ty);
        let freed = self.table(scope).get(name).map_or(0, Variable::bytes);
        self.memory.check(name, bytes, freed)?;
        let mut var = Variable::new(ty, dims, total);
        match init {
            Init::None => {}
            Init::List(values) => var.put_list(name, 0, values)?,
            Init::Repeat(value, count) => var.put_fill(name, 0, value, count)?,
        }
        self.memory.take(bytes, freed);
        self.table(scope).declare(name, var);
        Ok(())
    }

    fn table(&mut self, scope: Scope) -> &mut Table {
        match scope {
            Scope::Local => &mut self.levels[self.depth - 1],
            Scope::Global => &mut self.globals,
        }
    }

    /// The variable `name` as the current level sees it.
    pub fn get(&self, name: &str) -> Option<&Variable> {
        let current = &self.levels[self.depth - 1];
        if let Some(v) = current.get(name) {
            return Some(v);
        }
        if self.lud_extended_scope
            && self.depth > 1
            && let Some(v) = self.levels[0].get(name)
        {
            return Some(v);
        }
        self.globals.get(name)
    }

    fn get_mut(&mut self, name: &str) -> Option<&mut Variable> {
        let depth = self.depth;
        // Two lookups rather than one borrow held across branches.
        if self.levels[depth - 1].index.contains_key(name) {
            return self.levels[depth - 1].get_mut(name);
        }
        if self.lud_extended_scope && depth > 1 && self.levels[0].index.contains_key(name) {
            return self.levels[0].get_mut(name);
        }
        self.globals.get_mut(name)
    }

    /// Whether `name` is a variable the current level sees.
    pub fn is_defined(&self, name: &str) -> bool {
        self.get(name).is_some()
    }

    /// The R parameter `index`.
    pub fn r(&self, index: i32) -> Result<f64, RunError> {
        usize::try_from(index)
            .ok()
            .and_then(|i| self.r.get(i))
            .copied()
            .ok_or_else(|| self.r_out_of_range(index))
    }

    /// Sets the R parameter `index`.
    pub fn set_r(&mut self, index: i32, value: f64) -> Result<(), RunError> {
        match usize::try_from(index).ok().filter(|&i| i < self.r.len()) {
            Some(i) => {
                self.r[i] = value;
                Ok(())
            }
            None => Err(self.r_out_of_range(index)),
        }
    }

    fn r_out_of_range(&self, index: i32) -> RunError {
        RunError::new(
            codes::run::INDEX_OUT_OF_RANGE,
            format!(
                "R{index} is outside R0…R{} (MD28050 $MC_MM_NUM_R_PARAM)",
                self.r.len().saturating_sub(1)
            ),
        )
    }

    /// Reads `R[i]` or a user variable (`name`, element `indices`).
    /// System variables are not here: see
    /// [`RuntimeInterface`](crate::eval::RuntimeInterface).
    pub fn read(&self, kind: VarKind, name: &str, indices: &[i32]) -> Result<RtValue, RunError> {
        match kind {
            VarKind::RParameter => match indices {
                [i] => Ok(RtValue::Real(self.r(*i)?)),
                _ => Err(r_index_count(indices.len())),
            },
            _ => match self.get(name) {
                Some(var) => var.read(name, indices),
                None => Err(undefined(name)),
            },
        }
    }

    /// Writes `value`, converted to the variable's type, to `R[i]` or a
    /// user variable's element.
    pub fn write(
        &mut self,
        kind: VarKind,
        name: &str,
        indices: &[i32],
        value: &RtValue,
    ) -> Result<(), RunError> {
        match kind {
            VarKind::RParameter => match indices {
                [i] => {
                    let v = value.to_real()?;
                    self.set_r(*i, v)
                }
                _ => Err(r_index_count(indices.len())),
            },
            _ => match self.get_mut(name) {
                Some(var) => var.write(name, indices, value),
                None => Err(undefined(name)),
            },
        }
    }

    /// Writes consecutive elements from the one `start` names on (all
    /// indices, or none for the first element), in storage order; `None`
    /// leaves its element as it is. More values than elements from
    /// `start` on is [`codes::run::INDEX_OUT_OF_RANGE`] and writes nothing.
    pub fn write_list(
        &mut self,
        kind: VarKind,
        name: &str,
        start: &[i32],
        values: &[Option<RtValue>],
    ) -> Result<(), RunError> {
        if kind == VarKind::RParameter {
            let first = r_start(start)?;
            self.check_r_span(first, values.len())?;
            self.work.spend(values.len())?;
            let mut converted = Vec::with_capacity(values.len());
            for v in values {
                converted.push(v.as_ref().map(RtValue::to_real).transpose()?);
            }
            for (i, v) in converted.into_iter().enumerate() {
                if let Some(v) = v {
                    self.r[first as usize + i] = v;
                }
            }
            return Ok(());
        }
        let var = self.get(name).ok_or_else(|| undefined(name))?;
        let first = var.start(name, start)?;
        check_span(name, first, values.len(), var.data.len())?;
        self.work.spend(values.len())?;
        let var = self.get_mut(name).ok_or_else(|| undefined(name))?;
        var.put_list(name, first, values)
    }

    /// `REP(value, count)`: `value` for `count` elements from the one
    /// `start` names on (to the end without `count`).
    pub fn fill(
        &mut self,
        kind: VarKind,
        name: &str,
        start: &[i32],
        value: &RtValue,
        count: Option<usize>,
    ) -> Result<(), RunError> {
        if kind == VarKind::RParameter {
            let first = r_start(start)? as usize;
            let count = count.unwrap_or(self.r.len().saturating_sub(first));
            self.check_r_span(first as i32, count)?;
            self.work.spend(count)?;
            let v = value.to_real()?;
            self.r[first..first + count].fill(v);
            return Ok(());
        }
        let var = self.get(name).ok_or_else(|| undefined(name))?;
        let first = var.start(name, start)?;
        let count = count.unwrap_or(var.data.len().saturating_sub(first));
        check_span(name, first, count, var.data.len())?;
        self.work.spend(count)?;
        let var = self.get_mut(name).ok_or_else(|| undefined(name))?;
        var.put_fill(name, first, value, Some(count))
    }

    fn check_r_span(&self, first: i32, count: usize) -> Result<(), RunError> {
        let first = usize::try_from(first).map_err(|_| self.r_out_of_range(first))?;
        if first.saturating_add(count) > self.r.len() {
            return Err(RunError::new(
                codes::run::INDEX_OUT_OF_RANGE,
                format!(
                    "{count} values from R{first} on go past R{}",
                    self.r.len().saturating_sub(1)
                ),
            ));
        }
        Ok(())
    }
}

fn r_start(start: &[i32]) -> Result<i32, RunError> {
    match start {
        [i] => Ok(*i),
        [] => Ok(0),
        _ => Err(r_index_count(start.len())),
    }
}

fn check_span(name: &str, first: usize, count: usize, len: usize) -> Result<(), RunError> {
    if first.saturating_add(count) > len {
        return Err(RunError::new(
            codes::run::INDEX_OUT_OF_RANGE,
            format!(
                "{count} values from element {first} on go past the {len} elements of `{name}`"
            ),
        ));
    }
    Ok(())
}

fn r_index_count(given: usize) -> RunError {
    RunError::new(
        codes::run::INDEX_COUNT,
        format!("an R parameter takes one index, not {given}"),
    )
}

pub(crate) fn undefined(name: &str) -> RunError {
    RunError::new(
        codes::run::UNDEFINED_VARIABLE,
        format!("`{name}` is not defined here"),
    )
}

/// Character `at` of the STRING variable `name` holding `s` does not
/// exist: [`codes::run::INDEX_OUT_OF_RANGE`], the length in characters.
fn outside_string(name: &str, at: i32, s: &str) -> RunError {
    RunError::new(
        codes::run::INDEX_OUT_OF_RANGE,
        format!(
            "character {at} of `{name}` is outside the string of {} characters",
            s.chars().count()
        ),
    )
}
