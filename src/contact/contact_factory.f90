!> The one place that turns a deck's method name into a contact method
!> (contact_method_t). Adding a method: its module (a type extending
!> contact_method_t), one case here, and its name in the deck table
!> (contact_deck). A unit test may register a method of its own under a
!> name (contact_method_register) without touching this module.
module contact_factory
  use contact_state, only: contact_method_t, contact_spec_t
  use contact_dam, only: dam_t
  use contact_dlm, only: dlm_t
  implicit none
  private
  public :: contact_method_new, contact_method_register, method_maker

  abstract interface
    !> Allocates a method of the registered type.
    subroutine method_maker(method)
      import :: contact_method_t
      class(contact_method_t), allocatable, intent(out) :: method
    end subroutine method_maker
  end interface

  !> A method registered at run time (tests).
  type :: registered_t
    character(len=8) :: name = ''
    procedure(method_maker), pointer, nopass :: make => null()
  end type registered_t

  type(registered_t), allocatable, save :: registered(:)

contains

  !> The method of a deck group, configured; reverse: for its reverse pass.
  !> single_part: every pair of the interface on part 0 (the method's
  !> choice). An unknown name is a programming error: the deck reader
  !> accepts only known names.
  subroutine contact_method_new(spec, reverse, method, single_part)
    type(contact_spec_t), intent(in) :: spec
    logical, intent(in) :: reverse
    class(contact_method_t), allocatable, intent(out) :: method
    logical, intent(out) :: single_part
    integer :: i
    select case (spec%method)
    case ('dam')
      allocate(dam_t :: method)
    case ('dlm')
      allocate(dlm_t :: method)
    case default
      if (allocated(registered)) then
        do i = 1, size(registered)
          if (registered(i)%name == spec%method) call registered(i)%make(method)
        end do
      end if
      if (.not. allocated(method)) error stop 'contact_factory: unknown contact method'
    end select
    call method%configure(spec, reverse, single_part)
  end subroutine contact_method_new

  !> Register a method under a name (not one of the built-in names).
  subroutine contact_method_register(name, make)
    character(len=*), intent(in) :: name
    procedure(method_maker) :: make
    type(registered_t), allocatable :: grown(:)
    integer :: n
    n = 0
    if (allocated(registered)) n = size(registered)
    allocate(grown(n + 1))
    if (n > 0) grown(:n) = registered
    grown(n + 1)%name = name
    grown(n + 1)%make => make
    call move_alloc(grown, registered)
  end subroutine contact_method_register

end module contact_factory
