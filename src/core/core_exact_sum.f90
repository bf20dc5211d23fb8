!> Exact sums of reals, independent of the order of their terms.
!>
!> Every finite double is an integer multiple of 2^-1074; an exact_sum_t
!> holds the sum of its terms as a fixed-point integer of that unit, in limbs
!> of 32 bits kept in 64-bit integers (headroom for 2^30 additions between
!> carry propagations). Integer addition is associative, so the accumulated
!> integer, and the double made from it, do not depend on the order of the
!> terms, on how they were split among ranks, or on the rank count: the
!> reduction over ranks (par_sum_exact in parallel_env) adds normalised limbs
!> as integers. The value is the exact sum rounded to a double (within one
!> ulp of the correctly rounded sum, always the same for the same integer).
!> Used for the history's global sums, which are then bitwise identical on
!> any rank count and across restarts.
module core_exact_sum
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_value, ieee_quiet_nan
  use core_kinds, only: rk, i8
  implicit none
  private
  public :: exact_value, exact_pack, exact_unpack

  !> Limbs: bit 0 of limb 0 is 2^-1126 (below the smallest subnormal's
  !> mantissa once shifted), the largest double's top bit lands in limb 67,
  !> the rest is room for carries.
  integer, parameter, public :: EXACT_LIMBS = 72
  integer, parameter :: BIAS = 1126
  integer(i8), parameter :: MASK32 = 4294967295_i8
  integer, parameter :: NORMALISE_EVERY = 2**30

  !> An exact sum (start: a default-initialised value is 0).
  type, public :: exact_sum_t
    integer(i8) :: limb(0:EXACT_LIMBS - 1) = 0_i8
    integer(i8) :: nonfinite = 0_i8 !< terms that were Inf or NaN (the value is then NaN)
    integer :: adds = 0 !< additions since the last carry propagation
  contains
    procedure :: add => exact_add
    procedure :: normalise => exact_normalise
  end type exact_sum_t

  !> Values per packed exact sum (limbs and the non-finite count).
  integer, parameter, public :: EXACT_PACKED = EXACT_LIMBS + 1

contains

  !> acc = acc + x, exactly.
  subroutine exact_add(acc, x)
    class(exact_sum_t), intent(inout) :: acc
    real(rk), intent(in) :: x
    integer(i8) :: m, t0, t1, t2
    integer :: k, l, s
    if (x == 0.0_rk) return
    if (.not. ieee_is_finite(x)) then
      acc%nonfinite = acc%nonfinite + 1
      return
    end if
    ! |x| = m 2^(e - 53), m < 2^53 an integer; its lowest bit is bit k.
    m = int(scale(abs(fraction(x)), digits(x)), i8)
    k = exponent(x) - digits(x) + BIAS
    l = k / 32
    s = k - 32 * l
    t0 = iand(ishft(m, s), MASK32)
    t1 = iand(ishft(m, s - 32), MASK32)
    t2 = ishft(m, s - 64)
    if (x > 0.0_rk) then
      acc%limb(l) = acc%limb(l) + t0
      acc%limb(l + 1) = acc%limb(l + 1) + t1
      acc%limb(l + 2) = acc%limb(l + 2) + t2
    else
      acc%limb(l) = acc%limb(l) - t0
      acc%limb(l + 1) = acc%limb(l + 1) - t1
      acc%limb(l + 2) = acc%limb(l + 2) - t2
    end if
    acc%adds = acc%adds + 1
    if (acc%adds >= NORMALISE_EVERY) call acc%normalise()
  end subroutine exact_add

  !> Carry propagation: limbs 0 .. EXACT_LIMBS-2 in [0, 2^32), the top one
  !> signed (the sign of the sum). Same integer.
  subroutine exact_normalise(acc)
    class(exact_sum_t), intent(inout) :: acc
    integer :: i
    integer(i8) :: carry
    do i = 0, EXACT_LIMBS - 2
      carry = shifta(acc%limb(i), 32)
      acc%limb(i) = iand(acc%limb(i), MASK32)
      acc%limb(i + 1) = acc%limb(i + 1) + carry
    end do
    acc%adds = 0
  end subroutine exact_normalise

  !> The sum as a double: the top three non-zero limbs of its magnitude
  !> (96 bits) added from the largest; NaN when a term was not finite.
  real(rk) function exact_value(acc) result(v)
    type(exact_sum_t), intent(in) :: acc
    type(exact_sum_t) :: a
    logical :: negative
    integer :: i, h
    if (acc%nonfinite > 0) then
      v = ieee_value(1.0_rk, ieee_quiet_nan)
      return
    end if
    a = acc
    call a%normalise()
    negative = a%limb(EXACT_LIMBS - 1) < 0
    if (negative) then
      a%limb = -a%limb
      call a%normalise()
    end if
    v = 0.0_rk
    h = -1
    do i = EXACT_LIMBS - 1, 0, -1
      if (a%limb(i) /= 0) then
        h = i
        exit
      end if
    end do
    if (h < 0) return
    do i = h, max(h - 2, 0), -1
      v = v + scale(real(a%limb(i), rk), 32 * i - BIAS)
    end do
    if (negative) v = -v
  end function exact_value

  !> Normalised limbs and counts of sums into flat (EXACT_PACKED each), for
  !> an integer reduction.
  subroutine exact_pack(sums, flat)
    type(exact_sum_t), intent(inout) :: sums(:)
    integer(i8), intent(out) :: flat(:)
    integer :: j, o
    do j = 1, size(sums)
      call sums(j)%normalise()
      o = (j - 1) * EXACT_PACKED
      flat(o + 1:o + EXACT_LIMBS) = sums(j)%limb
      flat(o + EXACT_PACKED) = sums(j)%nonfinite
    end do
  end subroutine exact_pack

  !> The inverse of exact_pack (the limbs normalised again).
  subroutine exact_unpack(flat, sums)
    integer(i8), intent(in) :: flat(:)
    type(exact_sum_t), intent(inout) :: sums(:)
    integer :: j, o
    do j = 1, size(sums)
      o = (j - 1) * EXACT_PACKED
      sums(j)%limb = flat(o + 1:o + EXACT_LIMBS)
      sums(j)%nonfinite = flat(o + EXACT_PACKED)
      call sums(j)%normalise()
    end do
  end subroutine exact_unpack

end module core_exact_sum
