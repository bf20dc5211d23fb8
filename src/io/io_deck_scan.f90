!> Lexical scan of a namelist deck: finds every group instance (&name ... /)
!> and the keys assigned in it, so that unknown groups and keys are reported
!> all at once before any namelist read (which stops at the first bad key).
module io_deck_scan
  use core_status, only: status_t
  implicit none
  private
  public :: deck_scan, to_lower

  integer, parameter, public :: LINE_LEN = 512
  integer, parameter, public :: KEY_LEN = 64

  !> One group instance: its name, the deck lines it spans and its keys.
  type, public :: group_instance_t
    character(len=KEY_LEN) :: name = ''
    integer :: first_line = 0 !< line of '&name'
    integer :: last_line = 0 !< line of the closing '/'
    integer :: nkey = 0
    character(len=KEY_LEN), allocatable :: key(:) !< keys as written (lower case, no index)
  end type group_instance_t

contains

  !> Lower-case copy of a string.
  pure function to_lower(text) result(lower)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: lower
    integer :: i, code
    lower = text
    do i = 1, len(text)
      code = iachar(text(i:i))
      if (code >= iachar('A') .and. code <= iachar('Z')) lower(i:i) = achar(code + 32)
    end do
  end function to_lower

  pure logical function is_name_char(ch)
    character, intent(in) :: ch
    is_name_char = (ch >= 'a' .and. ch <= 'z') .or. (ch >= 'A' .and. ch <= 'Z') .or. &
        (ch >= '0' .and. ch <= '9') .or. ch == '_' .or. ch == '%'
  end function is_name_char

  !> Split the deck lines into group instances with their keys. Text outside
  !> groups must be blank or comments ('!' or '#').
  subroutine deck_scan(lines, groups, ngroup, status)
    character(len=LINE_LEN), intent(in) :: lines(:)
    type(group_instance_t), allocatable, intent(out) :: groups(:)
    integer, intent(out) :: ngroup
    type(status_t), intent(inout) :: status
    type(group_instance_t), allocatable :: tmp(:)
    integer :: il, ic, n, start, j, k
    logical :: in_group
    character :: ch, quote
    character(len=LINE_LEN) :: text
    character(len=16) :: lnum

    allocate(groups(8))
    ngroup = 0
    in_group = .false.
    quote = ' '
    do il = 1, size(lines)
      text = lines(il)
      n = len_trim(text)
      ic = 0
      do while (ic < n)
        ic = ic + 1
        ch = text(ic:ic)
        if (quote /= ' ') then
          if (ch == quote) quote = ' '
          cycle
        end if
        if (ch == '!' .or. (ch == '#' .and. .not. in_group)) exit
        if (.not. in_group) then
          if (ch == '&' .or. ch == '$') then
            start = ic + 1
            do while (ic < n)
              if (.not. is_name_char(text(ic + 1:ic + 1))) exit
              ic = ic + 1
            end do
            if (ngroup == size(groups)) then
              allocate(tmp(2 * ngroup))
              tmp(1:ngroup) = groups(1:ngroup)
              call move_alloc(tmp, groups)
            end if
            ngroup = ngroup + 1
            groups(ngroup)%name = to_lower(text(start:ic))
            groups(ngroup)%first_line = il
            allocate(groups(ngroup)%key(16))
            in_group = .true.
          else if (ch /= ' ' .and. ch /= achar(9)) then
            write(lnum, '(i0)') il
            call status%add('deck line '//trim(lnum)//': text outside any group: '''// &
                trim(adjustl(text))//'''')
            exit
          end if
        else
          if (ch == '''' .or. ch == '"') then
            quote = ch
          else if (ch == '/') then
            groups(ngroup)%last_line = il
            in_group = .false.
          else if (ch == '=') then
            ! The key is the name just before '=', after an optional (index).
            j = ic - 1
            do while (j >= 1)
              if (text(j:j) /= ' ') exit
              j = j - 1
            end do
            if (j >= 1) then
              if (text(j:j) == ')') then
                do while (j >= 1)
                  if (text(j:j) == '(') exit
                  j = j - 1
                end do
                j = j - 1
              end if
            end if
            k = j
            do while (k >= 1)
              if (.not. is_name_char(text(k:k))) exit
              k = k - 1
            end do
            if (j >= k + 1) call add_key(groups(ngroup), to_lower(text(k + 1:j)))
          end if
        end if
      end do
    end do
    if (in_group) then
      write(lnum, '(i0)') groups(ngroup)%first_line
      call status%add('&'//trim(groups(ngroup)%name)//': group opened on line '//trim(lnum)// &
          ' is never closed with ''/''')
      groups(ngroup)%last_line = size(lines)
    end if
  end subroutine deck_scan

  subroutine add_key(group, key)
    type(group_instance_t), intent(inout) :: group
    character(len=*), intent(in) :: key
    character(len=KEY_LEN), allocatable :: tmp(:)
    if (group%nkey == size(group%key)) then
      allocate(tmp(2 * group%nkey))
      tmp(1:group%nkey) = group%key(1:group%nkey)
      call move_alloc(tmp, group%key)
    end if
    group%nkey = group%nkey + 1
    group%key(group%nkey) = key
  end subroutine add_key

end module io_deck_scan
