!> Deck keys as data. Each package declares the keys of its deck group once,
!> in a table of key_t (name, value type, default, units, one-line meaning)
!> next to the group's reader; io_deck checks the deck against the tables
!> (unknown keys, value types), `impact3d --keys` prints them and the user
!> guide's key tables are checked against that print-out.
module core_keys
  use core_kinds, only: rk
  implicit none
  private
  public :: key_names, key_line

  integer, parameter, public :: KEY_LEN = 64 !< a key name as the deck scan holds it
  !> A real key's value before the deck's is read: still this after the read
  !> means the deck did not give the key.
  real(rk), parameter, public :: UNSET = -huge(1.0_rk)

  !> One deck key. type: 'r' real, 'i' integer, 'l' logical, 'c' character
  !> string; default as the user guide gives it ('required' when there is
  !> none); units the quantity (core_units: length, time, pressure, ...) or a
  !> unit of its own (K, s, degrees, cycles), '' when dimensionless or text.
  type, public :: key_t
    character(len=24) :: name
    character(len=1) :: type
    character(len=64) :: default
    character(len=24) :: units
    character(len=96) :: meaning
  end type key_t

contains

  !> The names of a table's keys, in table order.
  pure function key_names(keys) result(names)
    type(key_t), intent(in) :: keys(:)
    character(len=KEY_LEN) :: names(size(keys))
    integer :: k
    do k = 1, size(keys)
      names(k) = keys(k)%name
    end do
  end function key_names

  !> One key as `impact3d --keys` prints it, fields separated by ' | ':
  !> '&group | name | type | default | units | meaning' ('-' for no units).
  pure function key_line(group, key) result(line)
    character(len=*), intent(in) :: group
    type(key_t), intent(in) :: key
    character(len=:), allocatable :: line
    character(len=:), allocatable :: units
    units = trim(key%units)
    if (len(units) == 0) units = '-'
    line = '&'//group//' | '//trim(key%name)//' | '//type_name(key%type)//' | '// &
        trim(key%default)//' | '//units//' | '//trim(key%meaning)
  end function key_line

  pure function type_name(code) result(name)
    character, intent(in) :: code
    character(len=:), allocatable :: name
    select case (code)
    case ('r')
      name = 'real'
    case ('i')
      name = 'integer'
    case ('l')
      name = 'logical'
    case default
      name = 'text'
    end select
  end function type_name

end module core_keys
