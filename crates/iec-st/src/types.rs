//! Elementary types: widths, ranges, implicit widening and the wrap-around
//! representation every value is stored in.
//!
//! At run time every value lives in one `i64` cell: signed types
//! sign-extended, unsigned types and bit strings zero-extended, 64-bit
//! unsigned types as their raw bits, BOOL as 0 or 1. Arithmetic is done on
//! the `i64` with wrapping and then [`IntType::normalize`]d, which is
//! arithmetic modulo 2^width, as on a PLC.

use std::fmt;

/// An integer type or a bit string type (ANY_INT and ANY_BIT without BOOL).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IntType {
    /// 8-bit signed.
    Sint,
    /// 16-bit signed.
    Int,
    /// 32-bit signed.
    Dint,
    /// 64-bit signed.
    Lint,
    /// 8-bit unsigned.
    Usint,
    /// 16-bit unsigned.
    Uint,
    /// 32-bit unsigned.
    Udint,
    /// 64-bit unsigned.
    Ulint,
    /// 8-bit bit string.
    Byte,
    /// 16-bit bit string.
    Word,
    /// 32-bit bit string.
    Dword,
    /// 64-bit bit string.
    Lword,
}

/// Which implicit-widening chain a type belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// SINT, INT, DINT, LINT.
    Signed,
    /// USINT, UINT, UDINT, ULINT.
    Unsigned,
    /// BYTE, WORD, DWORD, LWORD.
    BitString,
}

impl IntType {
    /// Every integer and bit string type.
    pub const ALL: [IntType; 12] = [
        IntType::Sint,
        IntType::Int,
        IntType::Dint,
        IntType::Lint,
        IntType::Usint,
        IntType::Uint,
        IntType::Udint,
        IntType::Ulint,
        IntType::Byte,
        IntType::Word,
        IntType::Dword,
        IntType::Lword,
    ];

    /// The IEC keyword, upper case.
    pub fn name(self) -> &'static str {
        match self {
            IntType::Sint => "SINT",
            IntType::Int => "INT",
            IntType::Dint => "DINT",
            IntType::Lint => "LINT",
            IntType::Usint => "USINT",
            IntType::Uint => "UINT",
            IntType::Udint => "UDINT",
            IntType::Ulint => "ULINT",
            IntType::Byte => "BYTE",
            IntType::Word => "WORD",
            IntType::Dword => "DWORD",
            IntType::Lword => "LWORD",
        }
    }

    /// The type named `name` (any case).
    pub fn from_name(name: &str) -> Option<IntType> {
        IntType::ALL
            .into_iter()
            .find(|t| t.name().eq_ignore_ascii_case(name))
    }

    /// Width in bits.
    pub fn bits(self) -> u32 {
        match self {
            IntType::Sint | IntType::Usint | IntType::Byte => 8,
            IntType::Int | IntType::Uint | IntType::Word => 16,
            IntType::Dint | IntType::Udint | IntType::Dword => 32,
            IntType::Lint | IntType::Ulint | IntType::Lword => 64,
        }
    }

    /// The widening chain of the type.
    pub fn family(self) -> Family {
        match self {
            IntType::Sint | IntType::Int | IntType::Dint | IntType::Lint => Family::Signed,
            IntType::Usint | IntType::Uint | IntType::Udint | IntType::Ulint => Family::Unsigned,
            IntType::Byte | IntType::Word | IntType::Dword | IntType::Lword => Family::BitString,
        }
    }

    /// Two's complement signed?
    pub fn is_signed(self) -> bool {
        self.family() == Family::Signed
    }

    /// BYTE, WORD, DWORD or LWORD?
    pub fn is_bit_string(self) -> bool {
        self.family() == Family::BitString
    }

    /// Smallest value.
    pub fn min(self) -> i128 {
        if self.is_signed() {
            -(1i128 << (self.bits() - 1))
        } else {
            0
        }
    }

    /// Largest value.
    pub fn max(self) -> i128 {
        if self.is_signed() {
            (1i128 << (self.bits() - 1)) - 1
        } else {
            (1i128 << self.bits()) - 1
        }
    }

    /// Is `value` in the type's range?
    pub fn contains(self, value: i128) -> bool {
        (self.min()..=self.max()).contains(&value)
    }

    /// May a value of `self` be used where `to` is expected without an
    /// explicit conversion (same chain, not narrower)?
    pub fn widens_to(self, to: IntType) -> bool {
        self.family() == to.family() && self.bits() <= to.bits()
    }

    /// The stored cell of `raw` reduced modulo 2^width.
    #[inline]
    pub(crate) fn normalize(self, raw: i64) -> i64 {
        let bits = self.bits();
        if bits == 64 {
            raw
        } else if self.is_signed() {
            let shift = 64 - bits;
            (raw << shift) >> shift
        } else {
            raw & ((1i64 << bits) - 1)
        }
    }

    /// The mathematical value of a stored cell.
    pub(crate) fn value_of(self, cell: i64) -> i128 {
        if self.is_signed() {
            i128::from(cell)
        } else {
            i128::from(cell as u64)
        }
    }

    /// The stored cell of an in-range `value`.
    pub(crate) fn cell_of(self, value: i128) -> i64 {
        debug_assert!(self.contains(value));
        value as i64
    }
}

impl fmt::Display for IntType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The type of a scalar: BOOL or an integer/bit string type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Type {
    /// BOOL.
    Bool,
    /// An integer or bit string type.
    Int(IntType),
}

impl Type {
    /// The elementary type named `name` (any case).
    pub fn from_name(name: &str) -> Option<Type> {
        if name.eq_ignore_ascii_case("BOOL") {
            Some(Type::Bool)
        } else {
            IntType::from_name(name).map(Type::Int)
        }
    }

    /// May a value of `self` be assigned to `to` without a conversion?
    pub fn widens_to(self, to: Type) -> bool {
        match (self, to) {
            (Type::Bool, Type::Bool) => true,
            (Type::Int(a), Type::Int(b)) => a.widens_to(b),
            _ => false,
        }
    }

    /// The stored cell of the type's default value (FALSE, 0).
    pub(crate) const DEFAULT_CELL: i64 = 0;
}

impl fmt::Display for Type {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Type::Bool => f.write_str("BOOL"),
            Type::Int(t) => t.fmt(f),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_follow_the_width_and_signedness() {
        assert_eq!((IntType::Sint.min(), IntType::Sint.max()), (-128, 127));
        assert_eq!((IntType::Uint.min(), IntType::Uint.max()), (0, 65_535));
        assert_eq!(IntType::Ulint.max(), u64::MAX as i128);
        assert_eq!(IntType::Lint.min(), i64::MIN as i128);
        assert!(IntType::Byte.contains(255) && !IntType::Byte.contains(256));
    }

    #[test]
    fn widening_stays_within_one_chain() {
        assert!(IntType::Sint.widens_to(IntType::Lint));
        assert!(IntType::Usint.widens_to(IntType::Udint));
        assert!(IntType::Byte.widens_to(IntType::Dword));
        assert!(!IntType::Dint.widens_to(IntType::Int));
        assert!(!IntType::Usint.widens_to(IntType::Int));
        assert!(!IntType::Byte.widens_to(IntType::Uint));
        assert!(!Type::Bool.widens_to(Type::Int(IntType::Sint)));
    }

    #[test]
    fn normalize_reduces_modulo_the_width() {
        assert_eq!(IntType::Sint.normalize(128), -128);
        assert_eq!(IntType::Usint.normalize(-1), 255);
        assert_eq!(IntType::Udint.normalize(-2), 4_294_967_294);
        assert_eq!(IntType::Ulint.value_of(-1), u64::MAX as i128);
        assert_eq!(IntType::Word.normalize(0x1_2345), 0x2345);
    }
}
